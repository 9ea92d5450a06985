#include "io/snapshot_writer.hpp"

#include <algorithm>

#include "io/atomic_file.hpp"
#include "io/io_error.hpp"
#include "io/text_format.hpp"
#include "io/xyz_format.hpp"

namespace invasim {

namespace {

constexpr int kStepDigits = 9;

// A series' ParaView index: DIR/<kind>.pvd.
std::filesystem::path index_path(const std::filesystem::path& dir, const std::string& kind) {
  return dir / (kind + ".pvd");
}

}  // namespace

std::string SnapshotWriter::frame_file_name(const std::string& kind, std::uint64_t step,
                                            const std::string& extension) {
  std::string digits = std::to_string(step);
  if (digits.size() < std::size_t(kStepDigits))
    digits.insert(0, std::size_t(kStepDigits) - digits.size(), '0');
  return kind + "_" + digits + "." + extension;
}

std::int64_t SnapshotWriter::step_of_file_name(const std::string& name) {
  const std::size_t us = name.rfind('_');
  const std::size_t dot = name.rfind('.');
  if (us == std::string::npos || dot == std::string::npos || dot < us + 2) return -1;
  const std::string_view digits = std::string_view(name).substr(us + 1, dot - us - 1);
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  const auto v = text::parse<std::int64_t>(digits);
  return v ? *v : -1;
}

SnapshotWriter::SnapshotWriter(std::filesystem::path dir, SnapshotOptions options)
    : dir_(std::move(dir)), options_(options) {
  ensure_directory(dir_);
  if (options_.spheres_vtp) load_series(spheres_);
  if (options_.adipocytes_vtp) load_series(adipocytes_);
}

bool SnapshotWriter::is_own_frame(const std::string& kind, const std::string& file) const {
  const std::filesystem::path name(file);
  if (name.has_parent_path() || name.filename() != name) return false;
  if (file.rfind(kind + "_", 0) != 0 || name.extension() != ".vtp") return false;
  if (step_of_file_name(file) < 0) return false;
  std::error_code ec;
  return std::filesystem::symlink_status(dir_ / name, ec).type() ==
         std::filesystem::file_type::regular;
}

void SnapshotWriter::load_series(Series& s) {
  const std::filesystem::path pvd = index_path(dir_, s.kind);
  std::error_code ec;
  if (!std::filesystem::exists(pvd, ec)) return;
  s.entries = read_pvd(pvd);
  // Keep only the entries naming this series' own frame files that are there; a hand-edited
  // or damaged index (entries naming itself, another directory, a device) is rewritten.
  const std::size_t before = s.entries.size();
  std::erase_if(s.entries, [&](const PvdEntry& e) { return !is_own_frame(s.kind, e.file); });
  if (s.entries.size() != before) write_file_atomically(pvd, pvd_text(s.entries));
}

bool SnapshotWriter::drop_steps_from(Series& s, std::uint64_t first) {
  return std::erase_if(s.entries, [&](const PvdEntry& e) {
           const std::int64_t step = step_of_file_name(e.file);
           return step >= 0 && std::uint64_t(step) >= first;
         }) > 0;
}

void SnapshotWriter::add_to_series(Series& s, const Frame& frame, const std::string& file) {
  drop_steps_from(s, frame.step);  // a restart from an earlier checkpoint
  s.entries.push_back({frame.time, file});
  write_file_atomically(index_path(dir_, s.kind), pvd_text(s.entries));
}

void SnapshotWriter::forget_after(std::uint64_t step) {
  for (Series* s : {&spheres_, &adipocytes_})
    if (drop_steps_from(*s, step + 1))
      write_file_atomically(index_path(dir_, s->kind), pvd_text(s->entries));
}

SnapshotFiles SnapshotWriter::write(const System& sys) {
  return write(frame_from_system(sys, options_.ids));
}

SnapshotFiles SnapshotWriter::write(const Frame& frame) {
  SnapshotFiles out;
  auto put = [&](const std::string& name, const std::string& text) {
    write_file_atomically(dir_ / name, text);
    out.written.push_back(dir_ / name);
  };
  if (options_.cells_xyz) put(frame_file_name("cells", frame.step, "xyz"), xyz_frame_text(frame));
  if (options_.spheres_vtp) {
    const std::string name = frame_file_name("spheres", frame.step, "vtp");
    put(name, spheres_vtp_text(frame));
    add_to_series(spheres_, frame, name);
    out.written.push_back(dir_ / "spheres.pvd");
  }
  if (options_.adipocytes_vtp) {
    const std::string name = frame_file_name("adipocytes", frame.step, "vtp");
    put(name, adipocytes_vtp_text(frame));
    add_to_series(adipocytes_, frame, name);
    out.written.push_back(dir_ / "adipocytes.pvd");
  }
  if (options_.trajectory) {
    append_trajectory(frame);
    out.written.push_back(dir_ / "trajectory.xyz");
  }
  first_frame_ = false;
  return out;
}

void SnapshotWriter::append_trajectory(const Frame& frame) {
  const std::filesystem::path path = dir_ / "trajectory.xyz";
  if (first_frame_) truncate_xyz_trajectory(path, frame.step);
  append_file_synced(path, xyz_frame_text(frame));
}

void truncate_xyz_trajectory(const std::filesystem::path& path, std::uint64_t step) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return;
  const std::string text = read_file(path);
  // Walk complete frames; keep the prefix of frames with Step < step.
  std::size_t pos = 0, keep = 0;
  auto next_line = [&](std::string_view& line) {
    if (pos >= text.size()) return false;
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) return false;  // an unterminated line: incomplete frame
    line = std::string_view(text).substr(pos, end - pos);
    pos = end + 1;
    return true;
  };
  while (true) {
    std::string_view line;
    std::vector<std::string_view> tok;
    if (!next_line(line)) break;
    text::split_whitespace(line, tok);
    const auto n = tok.size() == 1 ? text::parse<std::size_t>(tok[0]) : std::nullopt;
    if (!n || !next_line(line)) break;
    const auto kv = parse_xyz_comment(line);
    const auto s = kv.find("Step");
    const auto frame_step = s == kv.end() ? std::nullopt : text::parse<std::uint64_t>(s->second);
    if (!frame_step || *frame_step >= step) break;
    bool complete = true;
    for (std::size_t i = 0; i < *n && complete; ++i) complete = next_line(line);
    if (!complete) break;
    keep = pos;
  }
  if (keep < text.size()) {
    std::filesystem::resize_file(path, keep, ec);
    if (ec) fail_io("cannot truncate ", quoted(path), ": ", ec.message());
  }
}

}  // namespace invasim
