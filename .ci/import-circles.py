#!/usr/bin/env python3
"""Import circles between the modules of a Rust source folder: `python3 .ci/import-circles.py vstf/src check` prints each circle (a set of modules importing one another) under `check` and fails if there is one."""
import re,os,sys
root=sys.argv[1]  # e.g. vstf/src
scope=sys.argv[2] # e.g. check  (module path prefix to inspect)
def modpath(f):
    rel=os.path.relpath(f,root)[:-3].split('/')
    if rel[-1] in('mod','lib'): rel=rel[:-1]
    return 'crate::'+'::'.join(rel) if rel else 'crate'
files={}
for d,_,fs in os.walk(root):
    for f in fs:
        if f.endswith('.rs'): files[modpath(os.path.join(d,f))]=os.path.join(d,f)
mods=set(files)
def resolve(path,cur):
    parts=path.split('::')
    if parts[0]=='super':
        base=cur.split('::')
        while parts and parts[0]=='super': parts=parts[1:]; base=base[:-1]
        parts=base+parts
    elif parts[0]=='self':
        parts=cur.split('::')+parts[1:]
    elif parts[0]!='crate': return None
    # longest module prefix
    for n in range(len(parts),0,-1):
        m='::'.join(parts[:n])
        if m in mods: return m
    return None
edges={m:set() for m in mods}
for m,f in files.items():
    s=open(f).read()
    s=re.sub(r'#\[cfg\(test\)\]\s*mod tests\s*\{.*','',s,flags=re.S)
    s=re.sub(r'//.*','',s)
    for p in re.findall(r'\b((?:crate|super|self)(?:::[A-Za-z_][A-Za-z_0-9]*)+)',s):
        t=resolve(p,m)
        if t and t!=m and not m.startswith(t+'::'): edges[m].add(t)
        elif t and m.startswith(t+'::') and t!=m: edges[m].add(t)  # child->ancestor import
    # use blocks with braces: crate::a::{b, c::D}
    for base,body in re.findall(r'\b((?:crate|super)(?:::[a-z_]+)*)::\{([^}]*)\}',s):
        for item in body.split(','):
            item=item.strip().split(' as ')[0]
            if not item: continue
            t=resolve(base+'::'+item,m)
            if t and t!=m: edges[m].add(t)
    for p in re.findall(r'^\s*(?:pub(?:\([a-z]+\))?\s+)?use\s+([a-z_][a-z_0-9]*)::',s,flags=re.M):
        if p in ('crate','super','self','std','core'): continue
        t=m+'::'+p
        if t in mods: edges[m].add(t)
# parent declares children (mod x;) is not an import edge
sub={m for m in mods if m=='crate::'+scope or m.startswith('crate::'+scope+'::')}
idx={};low={};st=[];on=set();out=[];c=[0]
sys.setrecursionlimit(10000)
def sc(v):
    idx[v]=low[v]=c[0];c[0]+=1;st.append(v);on.add(v)
    for w in edges[v]:
        if w not in sub: continue
        if w not in idx: sc(w);low[v]=min(low[v],low[w])
        elif w in on: low[v]=min(low[v],idx[w])
    if low[v]==idx[v]:
        comp=[]
        while True:
            w=st.pop();on.discard(w);comp.append(w)
            if w==v:break
        if len(comp)>1: out.append(comp)
for v in sorted(sub):
    if v not in idx: sc(v)
for comp in out: print('circle:',' '.join(sorted(comp)))
print(f'{len(sub)} modules under {scope}, {len(out)} circles')
sys.exit(1 if out else 0)
