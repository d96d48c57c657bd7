#!/bin/bash
# label: unsanitized
# Every relative link in README.md and docs/*.md points at a file or
# folder of the tree, and a link's #anchor (in the same or another
# Markdown file) names one of that file's headings, as GitHub spells them.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needPython
cd "$SRC" || fail "no source directory $SRC"
"$PY" - "$SRC" README.md docs/*.md <<'PY' > "$WORK/out" 2>&1 || fail "broken links: $(cat "$WORK/out")"
import os, re, sys
src, files = sys.argv[1], sys.argv[2:]
os.chdir(src)

def slug(heading):
    text = re.sub(r'[^\w\- ]', '', heading.strip().lower().replace('`', ''))
    return text.replace(' ', '-')

def body(path):
    # The text outside fenced code blocks and inline code spans.
    text = re.sub(r'^```.*?^```', '', open(path, encoding='utf-8').read(), flags=re.S | re.M)
    return re.sub(r'`[^`\n]*`', '', text)

def anchors(path):
    seen, out = {}, set()
    for line in body(path).split('\n'):
        m = re.match(r'^#+ (.*)$', line)
        if m:
            s = slug(m.group(1))
            n = seen.get(s, 0)
            seen[s] = n + 1
            out.add(s if n == 0 else f'{s}-{n}')
    return out

bad = []
for f in files:
    for target in re.findall(r'\]\(([^)\s]+)\)', body(f)):
        if re.match(r'^[a-z]+:', target):
            continue
        path, _, frag = target.partition('#')
        full = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
        if not os.path.exists(full):
            bad.append(f'{f}: ({target}): no such file {full}')
        elif frag and full.endswith('.md') and frag not in anchors(full):
            bad.append(f'{f}: ({target}): no heading #{frag} in {full}')
print('\n'.join(bad))
sys.exit(1 if bad else 0)
PY
grep -q '](docs/' README.md || fail "README.md links to nothing in docs/"
echo ok
