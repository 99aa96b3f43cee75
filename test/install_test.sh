#!/usr/bin/env bash
# The main job from an install tree: `cmake --install` into an empty prefix, then, from an
# empty working directory with no StickRep variable set, the all-in-one graph of the
# installed deploy/ must recover a correct pose and the installed tools must read their data
# from PREFIX/share/stickrep, not from the source tree.
# Usage: install_test.sh BUILD_DIR DOMAIN
set -euo pipefail
build_dir=$1
domain=$2
work=$(mktemp -d /tmp/stickrep_install_XXXXXX)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
mkdir -p "$work/cwd"
cmake --install "$build_dir" --prefix "$prefix" > "$work/install.log"
for f in bin/stickrep-launch bin/stickrep-whereami bin/stickrep-localizer \
         share/stickrep/configs/system.yaml share/stickrep/maps/engineering_building_3f.yaml \
         share/stickrep/deploy/virtual_robot.launch.yaml share/stickrep/idl/sensors.idl; do
  [[ -e "$prefix/$f" ]] || { echo "not installed: $f"; exit 1; }
done
cd "$work/cwd"
unset STICKREP_DATA_DIR STICKREP_CONFIG_DIR
# A tool: the map it reports must be the installed one.
"$prefix/bin/stickrep-whereami" --seed 101 -N 1 --threads 1 > whereami.txt
grep -qF "($prefix/share/stickrep/maps/engineering_building_3f.yaml)" whereami.txt ||
  { echo "stickrep-whereami did not read the installed map:"; head -3 whereami.txt; exit 1; }
# The main job, as the README runs it, from the install tree.
status=0
timeout 400 "$prefix/bin/stickrep-launch" "$prefix/share/stickrep/deploy/virtual_robot.launch.yaml" \
  --domain "$domain" > launch.txt 2>&1 || status=$?
if [[ $status -ne 0 ]] || ! grep -q "CORRECT" launch.txt || grep -q "INCORRECT" launch.txt; then
  echo "the main job from the install tree did not recover a correct pose (exit $status):"
  tail -30 launch.txt
  exit 1
fi
grep -o "pose recovered after [^:]*: ring '[^']*' edge [0-9]* [a-z]*" launch.txt | head -1
echo "installed into $prefix; main job CORRECT from an empty working directory"
