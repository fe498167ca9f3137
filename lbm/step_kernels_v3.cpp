// The LBM step compiled for x86-64-v3 (AVX2, FMA; CMake adds -march=x86-64-v3), with
// -ffp-contract=off (lbm/step_kernels.hpp; lbm/CMakeLists.txt sets this file's options).
#include "lbm/step_kernels.hpp"

namespace aniso::lbm {

extern const StepKernelTable x86_64_v3_step_kernels;
const StepKernelTable x86_64_v3_step_kernels{&stream_collide<float, false>, &stream_collide<float, true>,
                                             &stream_collide<double, false>, &stream_collide<double, true>};

} // namespace aniso::lbm
