#pragma once
// The LBM step (lbm/stream_collide.hpp) compiled for several x86-64 levels into one portable
// binary and chosen at run time for the CPU it runs on: the baseline (SSE2), x86-64-v3 (AVX2,
// FMA) and x86-64-v4 (AVX-512). Each is its own translation unit (step_kernels_*.cpp) with
// -ffp-contract=off, so that no level fuses a multiply and an add the baseline rounds twice:
// every level gives the same bits (tested), only faster. A native build (ANISO_NATIVE) carries
// the baseline alone, compiled for its own CPU.

#include "lbm/stream_collide.hpp"

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace aniso::lbm {

enum class InstructionSet { automatic, baseline, x86_64_v3, x86_64_v4 };

template <class Real>
using StepKernel = void (*)(Parity parity, Real* f, const std::uint32_t* slot, std::int64_t n_fluid,
                            std::int64_t stride, const std::array<Real, 3>& force, Real omega_plus,
                            Real omega_minus, MomentsRecord* moments);

/// One level's steps: without and with the moments record, in each precision.
struct StepKernelTable {
  StepKernel<float> float_step;
  StepKernel<float> float_measured;
  StepKernel<double> double_step;
  StepKernel<double> double_measured;

  template <class Real> [[nodiscard]] StepKernel<Real> step(bool measure) const {
    if constexpr (sizeof(Real) == sizeof(float))
      return measure ? float_measured : float_step;
    else
      return measure ? double_measured : double_step;
  }
};

/// "baseline", "x86-64-v3", "x86-64-v4" (the config's spelling), "auto".
[[nodiscard]] std::string_view instruction_set_name(InstructionSet set);

/// The levels this binary carries that this CPU runs, best first; the baseline always, last.
[[nodiscard]] std::vector<InstructionSet> runnable_instruction_sets();

/// `automatic` resolves to the best runnable level; a level this build or CPU lacks is an
/// InputError naming the levels it has.
[[nodiscard]] InstructionSet resolve_instruction_set(InstructionSet requested);

/// The steps of a resolved, runnable level.
[[nodiscard]] const StepKernelTable& step_kernels(InstructionSet resolved);

} // namespace aniso::lbm
