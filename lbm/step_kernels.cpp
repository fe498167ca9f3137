#include "lbm/step_kernels.hpp"

#include "common/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace aniso::lbm {

// Defined in step_kernels_<level>.cpp, each compiled for its level.
extern const StepKernelTable baseline_step_kernels;
#ifdef ANISO_LBM_X86_64_LEVELS
extern const StepKernelTable x86_64_v3_step_kernels;
extern const StepKernelTable x86_64_v4_step_kernels;
#endif

std::string_view instruction_set_name(InstructionSet set) {
  switch (set) {
  case InstructionSet::automatic: return "auto";
  case InstructionSet::baseline: return "baseline";
  case InstructionSet::x86_64_v3: return "x86-64-v3";
  case InstructionSet::x86_64_v4: return "x86-64-v4";
  }
  return "?";
}

std::vector<InstructionSet> runnable_instruction_sets() {
  std::vector<InstructionSet> sets;
#ifdef ANISO_LBM_X86_64_LEVELS
  // GCC's CPU test checks the OS saves the wider registers too (XCR0), not only CPUID.
  if (__builtin_cpu_supports("x86-64-v4")) sets.push_back(InstructionSet::x86_64_v4);
  if (__builtin_cpu_supports("x86-64-v3")) sets.push_back(InstructionSet::x86_64_v3);
#endif
  sets.push_back(InstructionSet::baseline);
  return sets;
}

InstructionSet resolve_instruction_set(InstructionSet requested) {
  const std::vector<InstructionSet> sets = runnable_instruction_sets();
  if (requested == InstructionSet::automatic) return sets.front();
  if (std::find(sets.begin(), sets.end(), requested) != sets.end()) return requested;
  std::vector<std::string_view> names;
  for (InstructionSet set : sets)
    names.push_back(instruction_set_name(set));
  throw InputError(fmt::format("lbm.instruction_set = \"{}\": this build or CPU cannot run it; it runs {} "
                               "(\"auto\" picks the first)",
                               instruction_set_name(requested), fmt::join(names, ", ")));
}

const StepKernelTable& step_kernels(InstructionSet resolved) {
  switch (resolved) {
#ifdef ANISO_LBM_X86_64_LEVELS
  case InstructionSet::x86_64_v4: return x86_64_v4_step_kernels;
  case InstructionSet::x86_64_v3: return x86_64_v3_step_kernels;
#endif
  default: return baseline_step_kernels;
  }
}

} // namespace aniso::lbm
