// The LBM step compiled for the baseline x86-64 level (SSE2), or the build's own CPU in a native build, with
// -ffp-contract=off (lbm/step_kernels.hpp; lbm/CMakeLists.txt sets this file's options).
#include "lbm/step_kernels.hpp"

namespace aniso::lbm {

extern const StepKernelTable baseline_step_kernels;
const StepKernelTable baseline_step_kernels{&stream_collide<float, false>, &stream_collide<float, true>,
                                            &stream_collide<double, false>, &stream_collide<double, true>};

} // namespace aniso::lbm
