# Shared by the scripts: where things are, and small helpers. Source it, do not run it.
# The repository is the catkin package; the workspace lives beside the sources in .ws/ (git-ignored)
# and reaches the package through a symlink, so the checkout itself is never written into except .ws/ and results/.
AP_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
AP_WS="${AP_WS:-$AP_ROOT/.ws}"
# The package's executables in the workspace (nodes, tools, tests).
BIN="$AP_WS/devel/lib/adaptive_perception"
# Debian's ROS Python modules live in the system python3; a pyenv python3 earlier on PATH lacks them.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
export PYTHONNOUSERSITE=1
unset PYTHONPATH PYENV_VERSION
# The indoor-simulator experiments (evaluate_places.sh, evaluate_room_classification.sh): the three
# lighting conditions and the seed base of each (training run base + 1, test run base + 2).
INDOOR_LIGHTS="night cloudy sunny"
indoor_seed_base() { case "$1" in night) echo 0 ;; cloudy) echo 10 ;; sunny) echo 20 ;; esac; }
# The value of KEY in a tool's `tool: key=value ...` summary line: summary_value "$line" KEY
summary_value() { echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
# A Markdown table's first two rows: the column names given, then a separator of as many columns.
md_header() {
  local names="|" rule="|" name
  for name in "$@"; do names+=" $name |"; rule+="---|"; done
  printf '%s\n%s\n' "$names" "$rule"
}
# A temporary folder in TMP, removed when the script exits.
make_tmp() { TMP="$(mktemp -d)"; trap 'rm -rf "$TMP"' EXIT; }
# The workspace's ROS environment, with ROS_HOME (logs, roslaunch's files) inside the workspace.
use_workspace() {
  set +u; source "$AP_WS/devel/setup.bash"; set -u
  export ROS_HOME="${ROS_HOME:-$AP_WS/ros_home}"
}
