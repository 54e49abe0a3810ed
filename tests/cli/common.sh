# Helpers shared by the CLI test scripts (POSIX sh), sourced after their `set` line:
#   . "$(dirname "$0")/common.sh"

# named_args NAME... -- ARG...: sets each NAME to the ARG in the same place, the scripts' usage
# line in code (stereo=$1, table=$2, ...). A missing ARG stops the script as `NAME=$N` would
# under `set -u`.
named_args() {
    _names=
    while [ "$1" != -- ]; do
        _names="$_names $1"
        shift
    done
    shift
    for _name in $_names; do
        eval "$_name=\$1"
        shift
    done
}

# fresh_work DIR [SUBDIR...]: DIR emptied of a previous run and made again, with each SUBDIR in
# it (DIR alone when none is named).
fresh_work() {
    _dir=$1
    rm -rf "$_dir"
    shift
    if [ "$#" -eq 0 ]; then
        mkdir -p "$_dir"
    else
        for _sub in "$@"; do mkdir -p "$_dir/$_sub"; done
    fi
}

# split_args USAGE ARGS_A... -- ARGS_B...: sets a to ARGS_A joined by spaces (split again into
# words where it is used) and a_count to how many arguments to shift so that "$@" holds ARGS_B;
# without the "--", prints "usage: USAGE" and exits 2.
split_args() {
    _usage=$1
    shift
    a=""
    a_count=1
    while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
        a="$a $1"
        a_count=$((a_count + 1))
        shift
    done
    [ "$#" -gt 0 ] || { echo "usage: $_usage"; exit 2; }
}

# untag IN OUT: a copy of the disparity PNG IN without the "stereo-disparity" tEXt chunk that
# `stereo` writes just before IEND (stereo_io/disparity_files.hpp), i.e. the PNG as another
# tool would have written it. IN must carry the chunk.
untag() {
    _at=$(grep -obUa 'tEXtstereo-disparity' "$1" | head -n 1 | cut -d: -f1)
    [ -n "$_at" ] || { echo "FAIL: $1 has no stereo-disparity chunk"; exit 1; }
    head -c $((_at - 4)) "$1" >"$2"
    tail -c 12 "$1" >>"$2"
}

# files_or_skip WHAT DIR FILE...: exits 77 (ctest's "skipped") with "SKIP: WHAT not found in DIR"
# unless every FILE is in DIR.
files_or_skip() {
    _what=$1
    _dir=$2
    shift 2
    for _file in "$@"; do
        if [ ! -f "$_dir/$_file" ]; then
            echo "SKIP: $_what not found in $_dir"
            exit 77
        fi
    done
}
