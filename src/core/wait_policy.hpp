#pragma once
// OpenMP wait policy for shared machines. libgomp's default lets idle threads spin at
// barriers and between parallel regions for ~0.3 ms; on a machine whose other cores are busy
// (other jobs of a sweep, other users) a spinning thread uses up its share of a core and is
// then descheduled while holding work, so a step with 2 threads became 3-4x slower than with 1.
// A passive policy makes waiting threads sleep, so the scheduler hands them a core as soon as
// they have work. libgomp reads its environment before main() runs, so the policy can only be
// changed by re-executing the program with it set.
namespace invasim {

// If neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT is set, sets OMP_WAIT_POLICY=passive and
// re-executes this program (/proc/self/exe) with the same arguments; returns (leaving the
// environment untouched) if either is set or the re-execution is impossible. Call first thing
// in main(), before any OpenMP call or output.
void use_passive_wait_policy_by_default(char** argv);

}  // namespace invasim
