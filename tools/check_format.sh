#!/usr/bin/env bash
# Fails if a C++ file differs from what the repository's .clang-format makes of it.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
git ls-files '*.cpp' '*.h' | xargs clang-format --dry-run --Werror
echo "== formatting: clean"
