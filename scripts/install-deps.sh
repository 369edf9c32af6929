#!/usr/bin/env bash
# Installs the Debian packages rayint builds, tests and reports with, only if missing.
set -euo pipefail
packages=(build-essential cmake pkg-config
          libboost-dev          # Boost.Math quadrature, Boost.Multiprecision, Boost.Odeint
          libeigen3-dev         # 3-D geometry: cells (Eq. 9), cameras, scenes
          libpng-dev            # PNG images: rendered output and background images
          libopenexr-dev        # OpenEXR float images: render -o x.exr, check --candidate-image x.exr
          libembree-dev         # Embree 3: first hit on tetrahedral mesh boundaries
          libcli11-dev          # command-line parsing of the rayint executable
          nlohmann-json3-dev    # case files and JSON reports
          catch2                # unit tests (Catch2 2.13)
          libcerf-dev           # erfcx and Dawson functions for the closed forms
          libhwy-dev            # Google Highway: vector erfcx/Dawson/exp of the batched exact path, one
                                #   binary that picks SSE4/AVX2/AVX-512 at run time (exact_batch)
          libbenchmark-dev      # Google Benchmark micro-benchmarks
          libpugixml-dev        # XML parser of the VTK XML readers (.vtu / .vti, input/vtk_xml_reader)
          zlib1g-dev            # inflating vtkZLibDataCompressor blocks in .vtu / .vti files
          liblz4-dev            # vtkLZ4DataCompressor blocks in .vtu / .vti files (LZ4_decompress_safe)
          liblzma-dev           # vtkLZMADataCompressor blocks in .vtu / .vti files (xz streams)
          python3-matplotlib    # plots in reports/
          pybind11-dev          # the Python module (src/python/): pybind11 headers + CMake config
          python3-dev           # Python.h and the interpreter's config, to compile that module
          python3-numpy         # the module's array arguments and results (exact_pieces, ...)
          python3-pytest        # the module's tests (tests/python/, CTest test python_module)
          python3-setuptools python3-wheel python3-pip  # `pip install .` of the Python module
                                #   (pyproject.toml + setup.py; CTest python_pip_install)
          slurm-wlm munge)      # CTest slurm_cluster: a local Slurm cluster runs sharded jobs (scripts/slurm/)
# --test: also what only the test suite needs (scripts/test.sh):
if [ "${1:-}" = "--test" ]; then
  packages+=(python3-torch)  # rayint.torch's autograd.Function is checked with torch.autograd.gradcheck
fi                           #   (tests/python/test_grad.py); the module itself works without torch
. "$(dirname "$0")/script-setup.sh"
apt_install_missing "${packages[@]}"
