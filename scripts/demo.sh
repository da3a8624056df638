#!/usr/bin/env bash
# `make demo`: runs biovision_bringup's launch/demo.launch headless to completion and prints its report.
# SCENARIO=mission (default): the cognitive robot's find-and-return mission; SCENARIO=tabletop: the
# active-vision loop alone in the table-top world.
set -uo pipefail
cd "$(dirname "$0")/.."
out=$(realpath -m "${1:-out/demo}")
export PATH=/usr/bin:/bin:$PATH
set +u; source devel/setup.bash; set -u
export ROS_HOME=${ROS_HOME:-$PWD/build/ros_home}
mkdir -p "$out" "$ROS_HOME"
scenario=${SCENARIO:-mission}
rm -f "$out/mission.json" "$out/mission.md" "$out/path.csv" "$out/path.png" "$out/memory.db" "$out/memory.db.lock" "$out/report.json" "$out/report.md" "$out/fixations.json" "$out/fixations.md" "$out/pan.csv" \
  "$out/recognition.json" "$out/recognition.md" "$out/objects.bin" "$out/panel.png" "$out/pan.png" \
  "$out/rates.png" "$out/report.html" "$out/ltm.pgm" "$out/run_report.log"
# A private master port so a demo never talks to a roscore the user already runs.
port=$((20000 + RANDOM % 20000))
export ROS_MASTER_URI=http://localhost:$port
echo "demo: roslaunch biovision_bringup demo.launch scenario:=$scenario (master on port $port, output in $out)"
timeout 480 roslaunch -p "$port" biovision_bringup demo.launch scenario:="$scenario" output_dir:="$out" \
  >"$out/roslaunch.log" 2>&1
rc=$?
if [[ ! -f "$out/report.json" ]]; then
  echo "demo: no report written (roslaunch exit $rc); last lines of $out/roslaunch.log:"
  tail -n 30 "$out/roslaunch.log"
  exit 1
fi
# Pictures (panel.png from monitor_panel, pan.png, rates.png) and one self-contained report.html.
rosrun biovision_monitor run_report "$out" >"$out/run_report.log" 2>&1 ||
  { echo "demo: run_report failed:"; cat "$out/run_report.log"; }
# The report's title first, then the mission's outcome, then the rest of the report (topics, tf).
head -n 1 "$out/report.md"; echo
[[ -f "$out/mission.md" ]] && { cat "$out/mission.md"; echo; }
tail -n +2 "$out/report.md"
[[ -f "$out/fixations.md" ]] && { echo; cat "$out/fixations.md"; }
[[ -f "$out/recognition.md" ]] && { echo; cat "$out/recognition.md"; }
[[ -f "$out/report.html" ]] && { echo; echo "Pictures and report: $out/report.html"; }
echo "Logs: $out/roslaunch.log (the launch and the nodelets' messages), $ROS_HOME/log/latest/ (the Python nodes' own logs, rosout.log)"
/usr/bin/python3 -c 'import json,sys; sys.exit(0 if json.load(open(sys.argv[1]))["ok"] else 1)' "$out/report.json" || exit 1
if [[ $scenario == mission ]]; then
  # The demo fails when the mission did not run to an outcome; a mission that ran and failed (object
  # not found, base trapped) is a result, printed above.
  [[ -f "$out/mission.json" ]] || { echo "demo: no mission.json (see $out/roslaunch.log)"; exit 1; }
  /usr/bin/python3 -c 'import json,sys; sys.exit(0 if json.load(open(sys.argv[1]))["mission_started"] else 1)' "$out/mission.json"
fi
