#!/usr/bin/env bash
# Installs the Debian 12 packages invasim needs, only those missing. Run as root.
set -euo pipefail
# libpugixml-dev: reading .vtp/.pvd; nlohmann-json3-dev: JSON files and the sweep workspaces;
# zlib1g-dev: checkpoint CRC-32. python3-numpy and python3-matplotlib: scripts/plot_run.py;
# with python3-scipy also scripts/master_curve.py (the sweep analysis); librsvg2-bin:
# invasim render -o X.png. slurm-wlm munge: the Slurm sweep test (tests/app/sweep_slurm.sh
# starts a private single-node Slurm). voro++ and voro++-dev: the test of the Voronoi
# measurement against voro++'s program and library (tests/measure/check_voronoi_voro.py).
packages=(g++ cmake make libeigen3-dev liblua5.4-dev lua5.4 libcgal-dev libgmp-dev catch2
          libpugixml-dev nlohmann-json3-dev zlib1g-dev
          python3 python3-numpy python3-scipy python3-matplotlib librsvg2-bin
          slurm-wlm munge voro++ voro++-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "invasim: installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
fi
