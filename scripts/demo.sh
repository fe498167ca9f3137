#!/usr/bin/env bash
# The README's demo command: installs missing Debian packages (make among them),
# then builds and runs the default demo campaign (`make demo`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh demo
# The analyses of different checkpoints are independent: run them side by side.
exec make -j "$(nproc)" demo "$@"
