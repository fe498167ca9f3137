#!/usr/bin/env bash
# The README's test command: installs missing Debian packages (make among them),
# then builds and runs the test suite and the format check (`make test`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh test
exec make test "$@"
