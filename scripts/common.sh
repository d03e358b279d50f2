# Shared by setup.sh, demo.sh and run_tests.sh: where things are. Source it, do not run it.
# The repository is the catkin package; the workspace lives beside the sources in .ws/ (git-ignored)
# and reaches the package through a symlink, so the checkout itself is never written into except .ws/ and results/.
AP_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
AP_WS="${AP_WS:-$AP_ROOT/.ws}"
# Debian's ROS Python modules live in the system python3; a pyenv python3 earlier on PATH lacks them.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
export PYTHONNOUSERSITE=1
unset PYTHONPATH PYENV_VERSION
