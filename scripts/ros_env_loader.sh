#!/usr/bin/env bash
# roslaunch env-loader for the hosts of a multi-machine site (launch/crane.launch,
# docs/site.md): the system python with the ROS modules and this workspace's setup, then the
# command roslaunch gives. The repository (and its build/ws) must be at the same path on every
# host.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
# shellcheck disable=SC1091
source "$ROOT/build/ws/devel/setup.bash"
exec "$@"
