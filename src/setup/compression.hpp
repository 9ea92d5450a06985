#pragma once
// Athermal isotropic compression (docs/model.md, protocol step 2): scale the box and the body
// centres so that phi grows by a fixed fraction per step (adipocytes move rigidly), then
// minimise with FIRE; repeat until the total packing fraction reaches the target. The last
// step lands exactly on the target. Also the affine rescale to an adipocyte packing fraction
// (protocol step 6).
#include <functional>
#include <optional>

#include "integrate/fire.hpp"
#include "measure/packing.hpp"

namespace invasim {

struct CompressionParams {
  double target_phi = 0.72;
  double step = 0.03;  // Delta phi / phi per compression step
  FireParams fire;     // minimiser after each step
  std::size_t max_steps = 100000;
  void validate() const;
};

struct CompressionReport {
  std::size_t steps = 0;         // compression steps taken
  std::uint64_t fire_steps = 0;  // total FIRE iterations
  bool converged = true;         // every minimisation reached its tolerance
  double phi = 0.0;              // final total packing fraction
  Vec3 box_lengths = Vec3::Zero();
  double max_force = 0.0;  // after the last minimisation
  bool stopped = false;    // stopped before the target was reached (callback or stop request)
  // Set when a stop request ended the run inside a step's FIRE (the step's scaling done): the
  // minimiser's state, from which compress_to_phi continues that FIRE.
  std::optional<FireState> fire_state;
};

// Called after each compression step with the report so far (progress display); returns
// false to stop there (a stop signal: the tissue is then a converged state of a compression
// step, from which compress_to_phi continues bit for bit).
using CompressionCallback = std::function<bool(const CompressionReport&)>;

// Polled before every FIRE iteration: true ends the compression there (a SIGINT/SIGTERM; near
// jamming one step's FIRE takes 1e4-1e5 iterations, longer than a batch system waits).
using CompressionStop = std::function<bool()>;

// Compresses to params.target_phi. `so_far` is the report of an earlier, stopped call on
// this system (its counters continue, and its fire_state, if any, continues the FIRE it
// stopped in; default: a fresh compression). Stopped and continued equals uninterrupted, bit
// for bit.
CompressionReport compress_to_phi(System& sys, ForceField& ff, const CompressionParams& params,
                                  const CompressionCallback& on_step = {},
                                  const CompressionReport& so_far = {},
                                  const CompressionStop& stop = {});

// Affine rescale of the box, the cancer cells and the adipocyte centres (adipocytes move
// rigidly, keeping their shape and V_i) so that the adipocyte
// packing fraction becomes phi_a, then FIRE. Returns the minimiser result.
// `control` (optional): its stop function ends the FIRE early (result.stopped).
FireResult rescale_to_phi_a(System& sys, ForceField& ff, double phi_a, const FireParams& fire,
                            const FireControl* control = nullptr);

}  // namespace invasim
