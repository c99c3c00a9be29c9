#!/usr/bin/env python3
"""libdirt.so exports exactly what the installed headers declare.

usage: test_symbols.py LIBDIRT_SO INCLUDE_DIR CC HEADER...

The oracle is the headers themselves: INCLUDE_DIR/HEADER... (the installed
set) are preprocessed with the C library's headers replaced by a few
typedefs and parsed with pycparser (Debian's python3-pycparser, which cffi
uses); every function declaration and every extern object declared there
is expected. The library's defined dynamic symbols (nm -D --defined-only)
must be that set: no more (an internal function or a third-party symbol
leaking), no fewer (a consumer declaration without DIRT_API, or never
defined). Exit 0 when they agree; 1 with the differences otherwise.
"""
import os
import subprocess
import sys
import tempfile

from pycparser import c_ast, c_parser

LIBC = {
    "stdbool.h": "typedef _Bool bool;\n",
    "stddef.h": "typedef unsigned long size_t;\n",
    "stdint.h": "".join("typedef %s %s;\n" % p for p in [
        ("signed char", "int8_t"), ("short", "int16_t"), ("int", "int32_t"),
        ("long", "int64_t"), ("unsigned char", "uint8_t"), ("unsigned short", "uint16_t"),
        ("unsigned int", "uint32_t"), ("unsigned long", "uint64_t")]),
    "stdio.h": "typedef struct FILE FILE;\n",
    "stdarg.h": "typedef void *va_list;\n",
}


def declared(include, headers, cc):
    with tempfile.TemporaryDirectory() as stubs:
        for name, text in LIBC.items():
            with open(os.path.join(stubs, name), "w") as f:
                f.write(text)
        src = "".join('#include "%s"\n' % h for h in headers)
        out = subprocess.run(
            [cc, "-E", "-P", "-undef", "-nostdinc", "-D_Bool=int", "-I", stubs, "-I", include,
             "-x", "c", "-"], input=src, capture_output=True, text=True, check=True).stdout
    ast = c_parser.CParser().parse(out)
    names = set()
    for node in ast.ext:
        if isinstance(node, c_ast.Decl) and node.name:
            if isinstance(node.type, c_ast.FuncDecl) or "extern" in node.storage:
                names.add(node.name)
    return names


def exported(lib):
    out = subprocess.run(["nm", "-D", "--defined-only", lib], capture_output=True, text=True,
                         check=True).stdout
    return {line.split()[-1].split("@")[0] for line in out.splitlines() if line.strip()}


def main():
    if len(sys.argv) < 5:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    lib, include, cc, headers = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    want = declared(include, headers, cc)
    have = exported(lib)
    missing, extra = sorted(want - have), sorted(have - want)
    for name in missing:
        print("FAIL: declared in the installed headers, not exported: %s" % name)
    for name in extra:
        print("FAIL: exported, not declared in the installed headers: %s" % name)
    print("%d declared, %d exported; %d passed, %d failed"
          % (len(want), len(have), len(want & have), len(missing) + len(extra)))
    return 1 if missing or extra else 0


if __name__ == "__main__":
    sys.exit(main())
