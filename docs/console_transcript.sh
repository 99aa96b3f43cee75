#!/usr/bin/env bash
# Prints the transcript of docs/console.md: starts the main job's processes on this host (the
# virtual robot on the Engineering Building, seed 20261121, real time; the executive holds at
# the recovered pose) on domain $DOMAIN (default 77), runs every console verb against them,
# and stops them. Output lines are cut at 200 characters.
#
#   bash docs/console_transcript.sh [BUILD_DIR]      (default: build)
set -uo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "${1:-$root/build}" && pwd)/bin
domain=${DOMAIN:-77}
logs=$(mktemp -d)
pids=()

stop_stack() {
  [ ${#pids[@]} -eq 0 ] || kill -INT "${pids[@]}" 2> /dev/null
  wait 2> /dev/null
  [ -n "${KEEP_LOGS:-}" ] && echo "logs kept in $logs" >&2 || rm -rf "$logs"
}
trap stop_stack EXIT

console() { "$bin/stickrep-console" --domain "$domain" "$@"; }

# One verb as the operator types it, its output and its exit code.
run() {
  echo "\$ stickrep-console $*"
  console "$@" 2>&1 | cut -c1-200
  echo "(exit ${PIPESTATUS[0]})"
  echo
}

"$bin/stickrep-virtual-robot" --domain "$domain" \
  --config "$root/deploy/configs/virtual_robot_main_job.yaml" > "$logs/virtual_robot.log" 2>&1 &
pids+=($!)
for p in sonar camera locomotion landmark localizer executive; do
  "$bin/stickrep-$p" --domain "$domain" > "$logs/$p.log" 2>&1 &
  pids+=($!)
done
camera_pid=${pids[2]}

# The pose first: every verb then sees the whole stack at work.
for _ in $(seq 120); do
  status=$(console echo localization/pose --once --field status --timeout 5 2> /dev/null)
  [[ "$status" == *LOCALIZED* ]] && break
  sleep 1
done
echo "# stack on domain $domain; pose: $status"
echo

run list
run info robot/motion/command
run echo robot/odometry --once
run echo localization/pose --once --field best.ring_id
run hz robot/sonar --duration 3
run delay robot/camera/image --duration 3
run bw --duration 3
run status --once
run doctor
run pose --once
run pose --once --json
run pose --png "$logs/pose.png"
run goal wing1_corridor/50
# Bad input.
run goal nowhere/7
run echo robot/sonr --once
run hz mission/goal --timeout 2
run echo mission/goal_result --once --timeout 5
DOMAIN_EMPTY=$((domain + 1))
echo "\$ stickrep-console --domain $DOMAIN_EMPTY status --once --timeout 3"
"$bin/stickrep-console" --domain "$DOMAIN_EMPTY" status --once --timeout 3 2>&1 | cut -c1-200
echo "(exit ${PIPESTATUS[0]})"
echo
# The camera process stopped (SIGSTOP) 3 s into the doctor's 6 s watch of the timed topics
# (after its 4 s of discovery): its heartbeat's liveliness lapses.
echo "\$ stickrep-console doctor --watch 6     # the camera process stopped with SIGSTOP after 7 s"
console doctor --watch 6 > "$logs/doctor.txt" 2>&1 &
doctor_pid=$!
sleep 7
kill -STOP "$camera_pid"
wait "$doctor_pid"
rc=$?
cut -c1-200 "$logs/doctor.txt"
echo "(exit $rc)"
kill -CONT "$camera_pid"
