# Sourced by the h4cal_*_test.sh scripts, which ctest runs as SCRIPT H4CAL DIR: names the
# program and an emptied scratch directory, and defines fail.
h4cal=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
