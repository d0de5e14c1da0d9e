#!/usr/bin/env python3
"""Compile time and peak memory of every translation unit, for docs/performance.md.

Configures a fresh Release build whose compiler launcher is GNU time, builds it, and prints a
Markdown table (slowest first). Needs /usr/bin/time (Debian package 'time').

    python3 bench/compile_times.py [build-dir] [jobs]
"""
import os
import re
import shutil
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "build-compile-times")
jobs = sys.argv[2] if len(sys.argv) > 2 else "1"
log = os.path.join(build, "compile_times.log")
if not os.path.exists("/usr/bin/time"):
    sys.exit("needs /usr/bin/time: apt-get install time")
shutil.rmtree(build, ignore_errors=True)
os.makedirs(build)
launcher = ";".join(["/usr/bin/time", "-a", "-o", log, "-f", "TU %e %M %C"])
subprocess.run(["cmake", "-S", root, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                "-DCMAKE_CXX_COMPILER_LAUNCHER=" + launcher], check=True,
               stdout=subprocess.DEVNULL)
subprocess.run(["cmake", "--build", build, "-j", jobs], check=True, stdout=subprocess.DEVNULL)
rows = []
with open(log) as f:
    for line in f:
        m = re.match(r"TU (\S+) (\d+) .* -c (\S+)", line.strip())
        if m:
            seconds, kb, source = float(m.group(1)), int(m.group(2)), m.group(3)
            rows.append((seconds, kb / 1024.0, os.path.relpath(source, root)))
rows.sort(reverse=True)
print(f"| translation unit | seconds | peak MB |  (-j{jobs}, Release)")
print("|---|---|---|")
for seconds, mb, source in rows:
    print(f"| `{source}` | {seconds:.1f} | {mb:.0f} |")
print(f"| **total** | {sum(r[0] for r in rows):.0f} | |")
