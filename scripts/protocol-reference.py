#!/usr/bin/env python3
"""Runs the Python reference code of docs/protocol.md's appendices (A: the framer, B: the
session messages, C: the ant messages) as one program, so that every byte string, hash and
size the appendices assert still holds: an independent client is written from that document
alone, and its reference code must not drift from the Rust implementation (whose own tests
pin the same values). Exit status 0 when every assertion holds."""
import pathlib
import re
import sys

doc = pathlib.Path(__file__).resolve().parent.parent / "docs" / "protocol.md"
text = doc.read_text(encoding="utf-8")
start = text.find("\n## Appendix A")
if start < 0:
    sys.exit(f"{doc}: no '## Appendix A' heading")
blocks = re.findall(r"```python\n(.*?)```", text[start:], re.S)
if len(blocks) < 3:
    sys.exit(f"{doc}: expected the Python blocks of appendices A, B and C, found {len(blocks)}")
code = "\n".join(blocks)
exec(compile(code, f"{doc} (appendices)", "exec"), {"__name__": "protocol_reference"})
print(f"{doc.name}: {len(blocks)} reference blocks ran, every assertion held")
