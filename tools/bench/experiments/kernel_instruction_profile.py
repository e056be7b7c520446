#!/usr/bin/env python3
"""Instructions per machine instruction of a PoCL kernel object, from Callgrind.

Why: the VM has no hardware counters, and PoCL's cached kernel objects carry no line
tables, so `callgrind_annotate` can only say how many instructions each kernel function
retired. This joins Callgrind's per-address counts (`--dump-instr=yes`) with `objdump -d`
of the same object, so a loop's instructions can be read with how often each ran.

    valgrind --tool=callgrind --dump-instr=yes --callgrind-out-file=/tmp/cg.out \\
        build/release/geocold-cl scene.obj --device cpu --threads 1 --spp 40 --samples-per-pass 8 ...
    tools/bench/experiments/kernel_instruction_profile.py /tmp/cg.out [FUNCTION]

Prints each function of the kernel object with its total; with FUNCTION, its disassembly
with each instruction's count divided by the function's calls (the count of its first
instruction). The object is the first one whose path ends in `.so` under a `kcache`
folder (PoCL's cache), or --object.
"""
import argparse
import collections
import re
import subprocess
import sys


def parse_callgrind(path: str, want_object):
    """{object path: {function: Counter(address -> self count)}} for objects matching."""
    names = {"ob": {}, "fn": {}}
    costs = collections.defaultdict(lambda: collections.defaultdict(collections.Counter))
    obj = fn = None
    address = 0
    skip_next = False  # the line after calls= is a call's inclusive cost, not the caller's own
    position = re.compile(r"^(0x[0-9a-f]+|[+-]\d+|\*)\s+\S+\s+(\d+)")

    def compressed(kind, text):
        m = re.match(r"\((\d+)\)(?:\s+(.*))?", text)
        if m.group(2):
            names[kind][m.group(1)] = m.group(2)
        return names[kind].get(m.group(1))

    with open(path) as f:
        for line in f:
            if line.startswith("ob="):
                obj = compressed("ob", line[3:].strip())
            elif line.startswith("fn="):
                fn = compressed("fn", line[3:].strip())
            elif line.startswith(("cob=", "cfn=")):
                compressed(line[1:3], line[4:].strip())
            elif line.startswith("calls="):
                skip_next = True
            else:
                m = position.match(line)
                if not m:
                    continue
                a = m.group(1)
                if a.startswith("0x"):
                    address = int(a, 16)
                elif a[0] in "+-":
                    address += int(a)
                if skip_next:
                    skip_next = False
                elif obj and want_object(obj):
                    costs[obj][fn][address] += int(m.group(2))
    return costs


def disassembly(obj: str, function: str):
    """[(address, text)] of one function in obj."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", obj], capture_output=True, text=True, check=True)
    rows, inside = [], False
    for line in out.stdout.splitlines():
        head = re.match(r"^[0-9a-f]+ <(\S+)>:", line)
        if head:
            inside = head.group(1) == function
            continue
        m = re.match(r"^\s+([0-9a-f]+):\s+(.*)", line)
        if inside and m:
            rows.append((int(m.group(1), 16), m.group(2).strip()))
    return rows


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("callgrind_out")
    p.add_argument("function", nargs="?")
    p.add_argument("--object", help="substring of the kernel object's path (default: PoCL's kcache)")
    args = p.parse_args()
    want = (lambda o: args.object in o) if args.object else (lambda o: "kcache" in o and o.endswith(".so"))
    costs = parse_callgrind(args.callgrind_out, want)
    if not costs:
        print("kernel_instruction_profile: no kernel object in that profile", file=sys.stderr)
        return 1
    obj, functions = next(iter(costs.items()))
    print(obj)
    for name, counts in sorted(functions.items(), key=lambda kv: -sum(kv[1].values())):
        print(f"  {sum(counts.values()):>14,}  {name}")
    if args.function:
        counts = functions.get(args.function)
        rows = disassembly(obj, args.function)
        if not counts or not rows:
            print(f"kernel_instruction_profile: no {args.function} in {obj}", file=sys.stderr)
            return 1
        calls = counts[rows[0][0]]
        print(f"{args.function}: {calls:,} calls, {sum(counts.values()) / calls:.1f} instructions a call; "
              "per instruction, runs per call:")
        for address, text in rows:
            print(f"  {address:6x} {counts[address] / calls:7.2f}  {text}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
