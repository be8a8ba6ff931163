"""Annotates every .gltf with an external buffer under MODELS into its own new folder under OUT and bakes
the copy back: the triangle counts must be those of the input (issue 23; not run by CI, the samples are
not in the repository). Usage: python3 scripts/annotate-roundtrip.py CHAMFER MODELS OUT"""
import json, os, subprocess, sys, re, shutil
C, root, out = sys.argv[1:4]
shutil.rmtree(out, ignore_errors=True)
tri = re.compile(r': (\d+) triangles')
rows = []
for dirpath, _, files in os.walk(root):
    for f in files:
        if not f.endswith('.gltf'): continue
        p = os.path.join(dirpath, f)
        try: doc = json.load(open(p, encoding='utf-8'))
        except Exception as e: rows.append((p, 'json', str(e))); continue
        uris = [b.get('uri', '') for b in doc.get('buffers', [])]
        if not any(u and not u.startswith('data:') for u in uris): continue
        rel = os.path.relpath(p, root).replace('/', '__')
        d = os.path.join(out, rel[:-5]); os.makedirs(d)
        def bake(path):
            r = subprocess.run([C, 'bake', path, '-o', os.path.join(d, 'x.chamfer')], capture_output=True, text=True)
            m = tri.search(r.stdout)
            return (int(m.group(1)) if m and r.returncode == 0 else None), (r.stderr.strip().splitlines() or [''])[-1]
        before, err0 = bake(p)
        o = os.path.join(d, f)
        r = subprocess.run([C, 'annotate', p, '-o', o], capture_output=True, text=True)
        if r.returncode != 0:
            rows.append((p, 'annotate-failed', (r.stderr.strip().splitlines() or [''])[-1], before)); continue
        after, err1 = bake(o)
        rows.append((p, 'same' if before == after else 'DIFF', before, after, err0 if before is None else '', err1 if after is None else ''))
from collections import Counter
print(Counter(r[1] for r in rows))
for r in rows:
    if r[1] != 'same' or r[2] is None: print(r)
print('total', len(rows), 'baked+roundtrip equal with counts:', sum(1 for r in rows if r[1]=='same' and r[2] is not None))
sys.exit(1 if any(r[1] == 'DIFF' for r in rows) else 0)
