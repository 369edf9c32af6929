#!/usr/bin/python3
"""The numeric options of every rayint subcommand and the domain CLI11 checks for each on input.

Reads `rayint SUB [SUB2] --help` (nothing is run), and lists every option whose value is a
number (INT, UINT, FLOAT) with the validator its help shows (":POSITIVE", "in [0 - 4096]", ...).
An option without one has no declared domain: its domain is either checked in the command's
code (a one-line refusal, exit 2) or not at all -- the audit's list of what to look at. NaN and
infinities are refused centrally for every float option (cli/options.hpp).

Usage: /usr/bin/python3 scripts/option_domains.py build/rayint > reports/reliability/option_domains.md
"""
import re
import subprocess
import sys

RAYINT = sys.argv[1] if len(sys.argv) > 1 else "build/rayint"
OPTION = re.compile(r"^\s+((?:-\w,)?--[\w-]+)\s+((?:INT|UINT|FLOAT)\S*(?: in \[[^\]]*\])?)(.*)$")


def help_text(args):
    return subprocess.run([RAYINT] + args + ["--help"], capture_output=True, text=True).stdout


def subcommands(text):
    out, inside = [], False
    for line in text.splitlines():
        if line.startswith("Subcommands:"):
            inside = True
            continue
        if inside:
            m = re.match(r"^  (\S+)\s", line)
            if m:
                out.append(m.group(1))
            elif line.strip() == "" and out:
                inside = False
    return out


def main():
    rows = []
    for sub in subcommands(help_text([])):
        text = help_text([sub])
        nested = subcommands(text)
        for path in ([[sub]] if not nested else [[sub]] + [[sub, n] for n in nested]):
            for line in help_text(path).splitlines():
                m = OPTION.match(line)
                if not m:
                    continue
                name, spec = m.group(1), m.group(2)
                base, _, check = spec.partition(":")
                rows.append((" ".join(path), name.split(",")[-1], base, check or "(none declared)"))
    print("| subcommand | option | type | domain declared to CLI11 |")
    print("|---|---|---|---|")
    for r in rows:
        print("| %s | `%s` | %s | %s |" % r)
    none = sum(1 for r in rows if r[3] == "(none declared)")
    print()
    print("%d numeric options, %d with a declared domain, %d without (their domain is checked in the "
          "command's code or not at all)." % (len(rows), len(rows) - none, none))


main()
