// aniso-fabric: the paper's thirteen fabric measures, stress and correlations from checkpoints (section 3).
#include "common/cli.hpp"
#include "common/stage_stub.hpp"

int main(int argc, char** argv) {
  return aniso::cli::run(
      argc, argv, "aniso-fabric", [](int argc_, char** argv_, const aniso::mpi::Comm& comm) {
        return aniso::cli::run_pending_stage(
            argc_, argv_, comm,
            {"aniso-fabric",
             "the paper's thirteen fabric measures, stress and correlations from checkpoints (section 3)",
             "fabric", aniso::cli::InputKind::checkpoint, 5});
      });
}
