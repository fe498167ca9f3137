// aniso-probe: incremental stiffness from six oedometric probes of one checkpoint (section 5).
#include "common/cli.hpp"
#include "common/stage_stub.hpp"

int main(int argc, char** argv) {
  return aniso::cli::run(
      argc, argv, "aniso-probe", [](int argc_, char** argv_, const aniso::mpi::Comm& comm) {
        return aniso::cli::run_pending_stage(
            argc_, argv_, comm,
            {"aniso-probe", "incremental stiffness from six oedometric probes of one checkpoint (section 5)",
             "probe", aniso::cli::InputKind::checkpoint, 6});
      });
}
