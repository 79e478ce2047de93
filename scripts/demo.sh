#!/usr/bin/env bash
# make demo: drive the embedded simulated arm (filled in as the CLI grows).
set -euo pipefail
armctl=${1:-build/armctl}
"$armctl" --help
