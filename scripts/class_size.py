#!/usr/bin/env python3
"""The size of the class ViscoplasticContact<dim>: its member functions and
non-static data members (declared in include/viscoplastic_contact.h, nested
types not counted), and its longest function definitions in source/ (from
the `template <int dim>` line to the closing brace).

Usage: python3 scripts/class_size.py [--longest N] [ROOT]
"""
import glob
import os
import re
import sys

args = sys.argv[1:]
n_longest = 10
if args[:1] == ['--longest']:
    n_longest = int(args[1])
    args = args[2:]
root = args[0] if args else os.path.join(os.path.dirname(__file__), '..')

src = open(os.path.join(root, 'include', 'viscoplastic_contact.h')).read()
# strip comments (keep line numbers)
def strip_comments(s):
    s = re.sub(r'/\*.*?\*/', lambda m: re.sub(r'[^\n]', ' ', m.group()), s, flags=re.S)
    return re.sub(r'//[^\n]*', '', s)
s = strip_comments(src)
m = re.search(r'\bclass\s+ViscoplasticContact\s*\{', s)
start = m.end()
# find matching brace of class body
depth, i = 1, start
while depth:
    if s[i] == '{': depth += 1
    elif s[i] == '}': depth -= 1
    i += 1
body, body_off = s[start:i-1], start
def lineno(pos): return s.count('\n', 0, pos) + 1
# split into top-level declarations; skip nested braces
decls, cur, cur_start, j = [], '', None, 0
while j < len(body):
    c = body[j]
    if c == '{':
        # brace block: a function body, a nested type body, or a brace-initializer
        d, k = 1, j + 1
        while d:
            if body[k] == '{': d += 1
            elif body[k] == '}': d -= 1
            k += 1
        head = cur.strip()
        is_type = re.match(r'^(struct|class|union|enum)\b', head)
        if is_type or ')' in head and not re.search(r'=\s*$', head):
            decls.append((head, cur_start, 'body'))
            cur, cur_start = '', None
            j = k
            # nested struct ends with ';'
            while j < len(body) and body[j] in ' \n\t': j += 1
            if j < len(body) and body[j] == ';': j += 1
            continue
        cur += body[j:k]; j = k; continue
    if c == ';':
        decls.append((cur.strip(), cur_start, 'semi')); cur, cur_start = '', None
    else:
        if cur_start is None and not c.isspace(): cur_start = body_off + j
        cur += c
    j += 1
def strip_angles(t):
    out, d = '', 0
    for ch in t:
        if ch == '<': d += 1
        elif ch == '>': d = max(0, d - 1)
        elif d == 0: out += ch
    return out
funcs, data, types = [], [], []
for head, pos, kind in decls:
    h = re.sub(r'^(public|private|protected)\s*:\s*', '', head).strip()
    if not h: continue
    if re.match(r'^(struct|class|union|enum)\b', h):
        types.append((re.match(r'^\w+\s+(\w+)', h).group(1), lineno(pos), kind)); continue
    if h.startswith('friend '): continue
    if h.startswith('using ') or h.startswith('typedef'): types.append((h, lineno(pos), 'alias')); continue
    flat = strip_angles(h.split('=')[0] if '(' not in h.split('=')[0] else h)
    mm = re.search(r'(~?\w+)\s*\(', flat)
    if mm and not re.search(r'=', flat[:mm.start()]):
        static = bool(re.match(r'^(static|inline static|static inline)\b', h))
        inline = kind == 'body'
        funcs.append((mm.group(1), lineno(pos), static, inline, ' '.join(h.split())))
    else:
        static = h.startswith('static')
        nm = re.search(r'(\w+)\s*(=.*)?$', strip_angles(h), re.S).group(1)
        data.append((nm, lineno(pos), static, ' '.join(h.split())))
def blank_comments_strings(s):
    s = re.sub(r'/\*.*?\*/', lambda m: re.sub(r'[^\n]', ' ', m.group()), s, flags=re.S)
    s = re.sub(r'//[^\n]*', lambda m: ' ' * len(m.group()), s)
    s = re.sub(r'"(\\.|[^"\\\n])*"', lambda m: '"' + ' ' * (len(m.group()) - 2) + '"', s)
    s = re.sub(r"'(\\.|[^'\\\n])'", lambda m: "' '" if len(m.group())==3 else ' '*len(m.group()), s)
    return s
rows = []
for f in sorted(glob.glob(os.path.join(root, 'source', '**', '*.cc'), recursive=True)):
    raw = open(f).read(); s = blank_comments_strings(raw)
    for m in re.finditer(r'ViscoplasticContact<dim>::(~?\w+)\s*\(', s):
        name = m.group(1)
        # find the '{' that opens the body (after the matching ')' of the parameter list)
        i, d = m.end(), 1
        while d:
            if s[i] == '(': d += 1
            elif s[i] == ')': d -= 1
            i += 1
        # after params: const, noexcept, ctor init list ... up to '{' or ';'
        j = i
        # skip ctor initializer list (may contain parens/braces)
        while s[j] not in '{;':
            if s[j] == '(':
                d = 1; j += 1
                while d:
                    if s[j] == '(': d += 1
                    elif s[j] == ')': d -= 1
                    j += 1
                continue
            j += 1
        if s[j] == ';': continue
        # ctor init list may use braces "x{...}" -- treat '{' preceded by identifier after ':' list
        k, d = j + 1, 1
        while d:
            if s[k] == '{': d += 1
            elif s[k] == '}': d -= 1
            k += 1
        # start: preceding 'template <int dim>' line
        t = s.rfind('template <int dim>', 0, m.start())
        start = s.count('\n', 0, t) + 1
        end = s.count('\n', 0, k - 1) + 1
        rows.append((name, os.path.relpath(f, root), start, end, end - start + 1))

ns = [d for d in data if not d[2]]
print(f'ViscoplasticContact<dim>: {len(funcs)} member functions '
      f'(constructor and destructor included), {len(ns)} data members')
print(f'longest definitions (lines):')
for name, path, start, end, n in sorted(rows, key=lambda r: -r[4])[:n_longest]:
    print(f'  {n:4d}  {name}  ({path}:{start})')
print(f'definitions of 100 lines or more: {sum(r[4] >= 100 for r in rows)}')
