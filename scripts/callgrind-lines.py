#!/usr/bin/env python3
"""Instruction counts of one source file's lines, inlined code included.

Reads a callgrind profile made with instruction-level positions, e.g.

  valgrind --tool=callgrind --dump-instr=yes --dump-line=no --callgrind-out-file=cg.out \\
      build/release/samples/tessera-render build/workloads/grid.tri -s 1 --repeat 1

and prints the binary's functions by self instructions, then the instructions of each line of
SOURCE (a file name such as setup_kernel.cpp): each executed instruction is charged to the
innermost frame of its inline chain (addr2line -i) that lies in SOURCE, so the Highway
operations a line calls count for that line. callgrind's counts repeat exactly from run to run,
where timings on a shared machine do not.

usage: scripts/callgrind-lines.py PROFILE BINARY SOURCE [LINES]
"""
import collections
import os
import re
import subprocess
import sys


def read_profile(path, binary_name):
    """Self instructions by address, and by function, for code in the binary."""
    names = {"ob": {}, "fn": {}}
    by_address, by_function = collections.Counter(), collections.Counter()
    obj = function = None
    address = 0
    after_call = False
    name_line = re.compile(r"(c?)(ob|fn)=\((\d+)\)(?: (.*))?")
    with open(path) as profile:
        for line in profile:
            match = name_line.match(line.rstrip("\n"))
            if match:
                called, kind, ident, name = match.groups()
                if name:
                    names[kind][ident] = name
                if not called:
                    if kind == "ob":
                        obj = names["ob"].get(ident)
                    else:
                        function = names["fn"].get(ident)
                continue
            if line.startswith("calls="):
                after_call = True  # the next cost line is the call's inclusive cost
                continue
            if not line or line[0] not in "0123456789+-*":
                continue
            fields = line.split()
            position = fields[0]
            if position.startswith("0x"):
                address = int(position, 16)
            elif position[0] in "+-":
                step = int(position[1:], 0)
                address += step if position[0] == "+" else -step
            if after_call:
                after_call = False
                continue
            if len(fields) >= 2 and obj and os.path.basename(obj) == binary_name:
                count = int(fields[-1])
                by_address[address] += count
                by_function[function] += count
    return by_address, by_function


def inline_chains(binary, addresses):
    chains = {}
    for start in range(0, len(addresses), 2000):
        chunk = addresses[start:start + 2000]
        out = subprocess.run(["addr2line", "-i", "-a", "-f", "-C", "-e", binary] +
                             [f"0x{a:x}" for a in chunk],
                             capture_output=True, text=True, check=True).stdout.splitlines()
        current, frames = None, []
        for line in out:
            if re.fullmatch(r"0x[0-9a-f]+", line):
                if current is not None:
                    chains[current] = frames
                current, frames = int(line, 16), []
            else:
                frames.append(line)
        if current is not None:
            chains[current] = frames
    return chains


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    profile, binary, source = sys.argv[1:4]
    shown = int(sys.argv[4]) if len(sys.argv) > 4 else 40
    by_address, by_function = read_profile(profile, os.path.basename(binary))
    print("self instructions by function:")
    for function, count in by_function.most_common(10):
        print(f"{count / 1e6:10.1f}M  {(function or '?')[:110]}")
    chains = inline_chains(binary, list(by_address))
    by_line, total = collections.Counter(), 0
    for address, count in by_address.items():
        frames = chains.get(address, [])
        for location in frames[1::2]:
            if source in location:
                by_line[os.path.basename(location).split(" ")[0]] += count
                total += count
                break
    print(f"{source}: {total / 1e6:.1f}M instructions")
    running = 0
    for line, count in by_line.most_common(shown):
        running += count
        print(f"{100 * count / total:6.2f}% {100 * running / total:7.2f}% {count / 1e6:9.2f}M  {line}")


if __name__ == "__main__":
    main()
