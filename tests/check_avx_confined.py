#!/usr/bin/env python3
"""The 8-wide path's AVX2 and AVX-512 code stays in its namespaces (include/rt/bvh/dispatch.hpp).

A program compiled without AVX2 in its target holds the BVH three times: the
unit's own 4-wide path, the 8-wide one compiled under
target("avx2,bmi,bmi2,popcnt") and, with g++ and clang++, the 8-wide one
again with AVX-512 added; rt::accelerator enters each only after the CPU
test. Every instruction on 256-bit registers, and every BMI1, BMI2 or POPCNT
instruction, must therefore sit in a function of rt::bvh_w8, rt::bvh_w8_avx512
or their detail namespaces (or a lambda or template of theirs), and every
AVX-512 instruction (one on zmm, xmm16-31, ymm16-31 or an opmask register,
an embedded broadcast, vpternlog) in one of rt::bvh_w8_avx512: one elsewhere
(a shared template instantiated inside a section, say) could run on a CPU
without them. Reads the disassembly of PROGRAM (objdump -d -C) and prints
each function outside them that uses such an instruction; exits 1 if there
is one, or if no function of bvh_w8 uses a ymm register (nothing was
checked).
Usage: check_avx_confined.py OBJDUMP PROGRAM
"""

import os
import re
import subprocess
import sys


# BMI1, BMI2 and POPCNT mnemonics as objdump prints them (AT&T syntax, a tab
# before). Not tzcnt: compilers emit `rep bsf` for a bit scan on any x86-64,
# which a CPU without BMI1 runs as bsf and objdump prints as tzcnt.
BIT_INSTRUCTION = re.compile(r"\t(andn|bextr|blsi|blsmsk|blsr|bzhi|mulx|pdep|pext|rorx|sarx|shlx|shrx|popcnt)[lqw]?\s")


# AVX-512's registers (zmm, the upper 16 xmm and ymm, the opmasks), its
# embedded broadcasts and the instructions it alone has that compilers emit
# for 256-bit code (a sample: the registers catch most of the rest).
AVX512 = re.compile(r"%zmm|%[xy]mm(1[6-9]|2[0-9]|3[01])\b|%k[0-7]\b|\{1to|\t(vpternlog|vpcompress|vcompress|vpexpand|"
                    r"vexpand|vpermt2|vpermi2|vpro[lr]|vpcmpu?[bwdq]\s|k(mov|and|or|xor|not|test|ortest|shift))")


def main() -> int:
    objdump, program = sys.argv[1], sys.argv[2]
    if not os.path.exists(program):  # a build of the suites alone (rt_suites) makes no stage program
        print(f"SKIPPED: {program} was not built (this build made the test suites only)")
        return 77
    text = subprocess.run([objdump, "-d", "-C", "--no-show-raw-insn", program], check=True,
                          capture_output=True, text=True).stdout
    function, inside, outside = None, set(), set()
    for line in text.splitlines():
        m = re.match(r"^[0-9a-f]+ <(.*)>:$", line)
        if m:
            function = m.group(1)
            continue
        if function is None:
            continue
        in_avx512 = "bvh_w8_avx512::" in function
        in_section = in_avx512 or "bvh_w8::" in function
        if AVX512.search(line) and not in_avx512:
            outside.add(function)
        elif "%ymm" in line:
            (inside if in_section else outside).add(function)
        elif not in_section and BIT_INSTRUCTION.search(line):
            outside.add(function)
    for f in sorted(outside):
        print(f"{program}: expected ymm registers and BMI/POPCNT instructions only in rt::bvh_w8 and "
              f"rt::bvh_w8_avx512, AVX-512 only in the latter, found them in {f}")
    print(f"{len(inside)} functions of rt::bvh_w8 and rt::bvh_w8_avx512 use ymm registers, {len(outside)} others")
    if not inside:
        print(f"{program}: expected the 8-wide path's functions to use ymm registers, found none")
    return 0 if inside and not outside else 1


if __name__ == "__main__":
    sys.exit(main())
