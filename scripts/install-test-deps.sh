#!/usr/bin/env bash
# Installs what only the test suite needs (scripts/test.sh calls it), only if missing:
#   python3-torch   rayint.torch's torch.autograd.Function is checked with torch.autograd.gradcheck
#                   (tests/python/test_grad.py); the module itself works without torch.
set -euo pipefail
packages=(python3-torch)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi
