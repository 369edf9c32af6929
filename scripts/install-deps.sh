#!/usr/bin/env bash
# Installs the Debian packages rayint builds, tests and reports with, only if missing.
set -euo pipefail
packages=(build-essential cmake pkg-config
          libboost-dev          # Boost.Math quadrature, Boost.Multiprecision, Boost.Odeint
          libeigen3-dev         # 3-D geometry: cells (Eq. 9), cameras, scenes
          libpng-dev            # PNG images: rendered output and background images
          libembree-dev         # Embree 3: first hit on tetrahedral mesh boundaries
          libcli11-dev          # command-line parsing of the rayint executable
          nlohmann-json3-dev    # case files and JSON reports
          catch2                # unit tests (Catch2 2.13)
          libcerf-dev           # erfcx and Dawson functions for the closed forms
          libbenchmark-dev      # Google Benchmark micro-benchmarks
          python3-matplotlib    # plots in reports/
          slurm-wlm munge)      # CTest slurm_cluster: a local Slurm cluster runs sharded jobs (scripts/slurm/)
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
