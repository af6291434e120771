#!/usr/bin/env bash
# Installs the Debian packages the README's commands need (tools/common.sh lists them) with
# apt-get, only those missing.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
