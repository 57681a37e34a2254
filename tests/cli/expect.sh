#!/usr/bin/env bash
# expect.sh CODE REGEX COMMAND...: runs COMMAND, passes when it exits with CODE and its output (stdout and
# stderr together) matches the extended regular expression REGEX.
code=$1
regex=$2
shift 2
output=$("$@" 2>&1)
status=$?
if [ "$status" -ne "$code" ]; then
    echo "expected exit $code, got $status from: $*"
    echo "$output"
    exit 1
fi
if ! grep -Eq -- "$regex" <<<"$output"; then
    echo "output does not match /$regex/:"
    echo "$output"
    exit 1
fi
echo "ok: exit $status, output matches /$regex/"
