#!/usr/bin/env python3
"""Builds the generated part of the fuzz seed corpus from real exports.

    make_corpus.py EXPORT.jsonl [EXPORT.jsonl ...] EARC_DB OUT_DIR

Each export (earc-db export) is cut to a few rows with two-state paths (key
and cost kept consistent), written as a small export, imported with EARC_DB
into a small database (512-byte pages, rollback journal, so the file is a
few KiB), and each row's path and key blobs are written as path_blob seeds.
"""
import json, os, sqlite3, subprocess, sys, tempfile

exports, earc_db, out = sys.argv[1:-2], sys.argv[-2], sys.argv[-1]
rows = []
for path in exports:
    with open(path) as f:
        next(f)
        for line in list(f)[:2]:
            r = json.loads(line)
            r["paths"] = [[p[0], p[-1]] for p in r["paths"]]
            r["cost"] = float(len(r["paths"]))
            rows.append(r)
os.makedirs(f"{out}/import", exist_ok=True)
os.makedirs(f"{out}/path_blob", exist_ok=True)
export = f"{out}/import/tiny.jsonl"
with open(export, "w") as f:
    f.write(json.dumps({"format": "earc.experiences.v1", "rows": len(rows), "schema_version": 3}) + "\n")
    for r in rows:
        f.write(json.dumps(r) + "\n")
with tempfile.TemporaryDirectory() as tmp:
    db = f"{tmp}/tiny.db"
    subprocess.run([earc_db, "import", "--db", db, export], check=True, stdout=subprocess.DEVNULL)
    c = sqlite3.connect(db)
    c.execute("pragma journal_mode = delete")
    c.execute("pragma page_size = 512")
    c.execute("vacuum")
    for i, (key, paths) in enumerate(c.execute("select key, paths from experiences order by id")):
        open(f"{out}/path_blob/row{i}.paths", "wb").write(paths)
        open(f"{out}/path_blob/row{i}.key", "wb").write(key)
    c.close()
    os.replace(db, f"{out}/import/tiny.db")
