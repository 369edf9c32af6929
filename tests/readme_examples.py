#!/usr/bin/env python3
"""CTest test `readme_examples`: every example of README.md runs and prints what the README shows.

The examples are the ```console blocks of README.md. In such a block a line starting with `$ ` is a
command; the lines after it, up to the next command or the end of the block, are the output it
must print (stdout and stderr together, as a terminal shows them). A command ending in ` \\` is
continued on the next line. The output is compared line by line after trailing blanks are removed;
the only masking is `…` (U+2026), which matches any text within one line and is used for wall
times and for nothing else (never for an error value or a count).

A ```python (or other) block right after `<!-- file: PATH -->` must be exactly the file PATH.

Each block runs in one fresh temporary folder that holds a copy of `cases/`, `docs/examples/` and
an empty `out/`,
so the commands read the bundled files as they would from a checkout and write (into out/) only
there, never into the source tree. `rayint` is the built executable (its folder first on PATH);
`PYTHONPATH` holds the built Python module.

Usage: readme_examples.py SOURCE_DIR RAYINT_EXE [PYTHON_DIR] [--update-hint] [--only N] [--no-python] [--doc PATH]
  --doc PATH     the examples of another Markdown file (relative to SOURCE_DIR, e.g. docs/gradients.md:
                 CTest `docs_gradients_examples`) instead of README.md, with the same rules
  --no-python    the build has no Python module (the ASan+UBSan build: python3 cannot load an
                 instrumented module); blocks that run Python are reported as skipped, by count
  --update-hint  print, for every block that differs, the output the commands print now, in the
                 README's form (for regenerating the README after an intended change)
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile


DOC = "README.md"  # the file whose examples run (--doc)


def blocks(readme_text):
    """[(line_number, [(command, [expected lines])])] of the ```console blocks."""
    out = []
    lines = readme_text.split("\n")
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```console":
            start = i + 1
            body = []
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i])
                i += 1
            steps = []
            j = 0
            while j < len(body):
                line = body[j]
                if line.startswith("$ "):
                    cmd = line[2:]
                    while cmd.endswith("\\") and j + 1 < len(body):
                        j += 1
                        cmd = cmd[:-1] + "\n" + body[j]
                    steps.append((cmd, []))
                elif steps:
                    steps[-1][1].append(line)
                else:
                    raise SystemExit(f"{DOC}:{start + j}: output before the first `$ ` command")
                j += 1
            out.append((start, steps))
        i += 1
    return out


def matches(expected, got):
    if "…" not in expected:
        return expected == got
    pattern = ".*".join(re.escape(part) for part in expected.split("…"))
    return re.fullmatch(pattern, got) is not None


def clean(text):
    lines = [l.rstrip() for l in text.replace("\r\n", "\n").split("\n")]
    while lines and lines[-1] == "":
        lines.pop()
    return lines


def run_block(steps, source, env):
    """The failures of one block, and the actual outputs in README form."""
    failures = []
    actual = []
    with tempfile.TemporaryDirectory(prefix="rayint-readme-") as tmp:
        shutil.copytree(os.path.join(source, "cases"), os.path.join(tmp, "cases"))
        os.makedirs(os.path.join(tmp, "out"))  # the README's set-up: mkdir -p out
        if os.path.isdir(os.path.join(source, "docs", "examples")):
            shutil.copytree(os.path.join(source, "docs", "examples"), os.path.join(tmp, "docs", "examples"))
        for cmd, expected in steps:
            r = subprocess.run(["bash", "-c", cmd], cwd=tmp, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, timeout=900)
            got = clean(r.stdout)
            exp = clean("\n".join(expected))
            actual.append("$ " + cmd.replace("\n", " \\\n"))
            actual.extend(got)
            ok = len(got) == len(exp) and all(matches(e, g) for e, g in zip(exp, got))
            if not ok:
                failures.append(f"command: {cmd}\n  exit status {r.returncode}\n  expected:\n    " +
                                "\n    ".join(exp) + "\n  got:\n    " + "\n    ".join(got))
    return failures, actual


def uses_module(cmd, source):
    """Whether a command imports the rayint Python module (inline, or in a script it runs)."""
    if "import rayint" in cmd:
        return True
    for word in cmd.split():
        path = os.path.join(source, word)
        if word.endswith(".py") and os.path.isfile(path) and "import rayint" in open(path, encoding="utf-8").read():
            return True
    return False


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    update = "--update-hint" in sys.argv
    no_python = "--no-python" in sys.argv
    only = None
    if "--only" in sys.argv:
        only = int(sys.argv[sys.argv.index("--only") + 1])
        args = [a for a in args if a != str(only)]
    global DOC
    if "--doc" in sys.argv:
        DOC = sys.argv[sys.argv.index("--doc") + 1]
        args = [a for a in args if a != DOC]
    if len(args) < 2:
        raise SystemExit(__doc__)
    source, exe = os.path.abspath(args[0]), os.path.abspath(args[1])
    env = dict(os.environ)
    env["PATH"] = os.path.dirname(exe) + os.pathsep + env.get("PATH", "")
    if len(args) > 2:
        env["PYTHONPATH"] = os.path.abspath(args[2])
    env["LC_ALL"] = "C.UTF-8"
    readme = open(os.path.join(source, DOC), encoding="utf-8").read()
    found = blocks(readme)
    # A code block shown as a file's content (`<!-- file: PATH -->` before it) is that file.
    bad_files = 0
    for m in re.finditer(r"<!-- file: (\S+) -->\n```\w*\n(.*?)```", readme, re.S):
        if open(os.path.join(source, m.group(1)), encoding="utf-8").read() != m.group(2):
            print(f"{DOC} shows {m.group(1)}, but the file differs")
            bad_files += 1
    if not found:
        raise SystemExit(f"{DOC} has no ```console examples")
    bad = skipped = 0
    for n, (line, steps) in enumerate(found):
        if only is not None and n != only:
            continue
        if no_python and any(uses_module(cmd, source) for cmd, _ in steps):
            print(f"example {n} ({DOC} line {line}, {len(steps)} commands): SKIPPED (no Python module in this build)")
            skipped += 1
            continue
        failures, actual = run_block(steps, source, env)
        status = "ok" if not failures else "DIFFERS"
        print(f"example {n} ({DOC} line {line}, {len(steps)} commands): {status}")
        for f in failures:
            print("  " + f.replace("\n", "\n  "))
        if failures:
            bad += 1
            if update:
                print("  now, in README form:\n```console\n" + "\n".join(actual) + "\n```")
    print(f"{len(found)} examples, {bad} differ, {skipped} skipped; {bad_files} shown files differ")
    return 1 if bad or bad_files else 0


if __name__ == "__main__":
    sys.exit(main())
