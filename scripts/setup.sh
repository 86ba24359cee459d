#!/bin/sh
# Installs what librugo needs on a Debian machine, if anything is missing.
# As root it runs apt-get; otherwise it prints the exact install line and stops with status 1.
set -eu
# The testbed (samples/testbed, docs/testbed.md): GLFW, Dear ImGui (its GLFW and OpenGL 3 backends are in
# libimgui-dev's libimgui.a) and, for its headless test, an X server in memory (xvfb-run needs xauth) with
# Mesa's software OpenGL (libgl1-mesa-dri); mesa-utils has glxinfo, to see which OpenGL a machine has.
PACKAGES="cmake make gcc g++ pkg-config check libeigen3-dev libbox2d-dev clang libclang-rt-14-dev doxygen clang-format
libglfw3-dev libimgui-dev xvfb xauth mesa-utils libgl1-mesa-dri"
missing=""
for p in $PACKAGES; do
    # "installed" exactly: a removed package whose configuration files remain is not installed.
    [ "$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null)" = installed ] || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -eq 0 ]; then
    echo "setup: installing$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends $missing
else
    echo "setup: missing packages; run this as root, then try again:" >&2
    echo "  apt-get update && apt-get install -y$missing" >&2
    exit 1
fi
