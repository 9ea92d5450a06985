// The faces of every Voronoi cell from the voro++ library at full precision (the voro++
// program prints areas with 6 significant digits): the same container as
//   voro++ -py -pz [-r] -c "%i %n %f" x_lo x_hi y_lo y_hi z_lo z_hi FILE
// (walls in x, periodic y and z; with "radical", FILE has a radius column), one line per cell
// on stdout: the particle id, its neighbours' ids (-1, -2: the walls x = x_lo, x = x_hi), then
// the face areas in the same order, with 17 significant digits.
// Usage: voro_faces x_lo x_hi y_lo y_hi z_lo z_hi FILE [radical]
#include <voro++/voro++.hh>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

// Prints the cells of every particle of a container.
template <class Container>
int print_cells(Container& con) {
  voro::c_loop_all loop(con);
  voro::voronoicell_neighbor cell;
  std::vector<int> neighbours;
  std::vector<double> areas;
  if (loop.start()) do {
      if (!con.compute_cell(cell, loop)) continue;
      cell.neighbors(neighbours);
      cell.face_areas(areas);
      std::printf("%d", loop.pid());
      for (int n : neighbours) std::printf(" %d", n);
      for (double a : areas) std::printf(" %.17g", a);
      std::printf("\n");
    } while (loop.inc());
  return 0;
}

// Number of lines (particles) in the file.
int count_lines(const char* path) {
  FILE* f = std::fopen(path, "r");
  if (!f) return -1;
  int n = 0;
  for (int ch; (ch = std::fgetc(f)) != EOF;) n += ch == '\n';
  std::fclose(f);
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 8 && !(argc == 9 && std::strcmp(argv[8], "radical") == 0)) {
    std::fprintf(stderr, "usage: voro_faces x_lo x_hi y_lo y_hi z_lo z_hi FILE [radical]\n");
    return 2;
  }
  double b[6];
  for (int k = 0; k < 6; ++k) b[k] = std::atof(argv[k + 1]);
  const int n = count_lines(argv[7]);
  if (n < 1) {
    std::fprintf(stderr, "voro_faces: cannot read particles from %s\n", argv[7]);
    return 1;
  }
  // Blocks of about 5 particles each, as the voro++ program chooses them.
  const double volume = (b[1] - b[0]) * (b[3] - b[2]) * (b[5] - b[4]);
  const double side = std::cbrt(5.0 * volume / n);
  int blocks[3];
  for (int a = 0; a < 3; ++a) blocks[a] = std::max(1, int((b[2 * a + 1] - b[2 * a]) / side + 0.5));
  if (argc == 9) {
    voro::container_poly con(b[0], b[1], b[2], b[3], b[4], b[5], blocks[0], blocks[1], blocks[2],
                             false, true, true, 8);
    con.import(argv[7]);
    return print_cells(con);
  }
  voro::container con(b[0], b[1], b[2], b[3], b[4], b[5], blocks[0], blocks[1], blocks[2], false,
                      true, true, 8);
  con.import(argv[7]);
  return print_cells(con);
}
