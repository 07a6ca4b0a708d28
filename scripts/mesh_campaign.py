#!/usr/bin/env python3
"""A bounded robustness campaign against the mesh readers (docs/reliability.md,
"Mesh readers"): writes a 200-triangle grid in every format the importer
reads, mutates it the ways a hostile or unlucky user would (cut short, bytes
flipped, header counts raised and lowered, indices out of range, material
libraries naming devices, non-regular files) and tries numeric extremes of the
import options, then runs `hybridscape-cli import` on each case with a time
and memory limit and sorts the outcome:

  refused   non-zero exit with a message naming the file or option
  accepted  exit 0 with all 200 triangles, or with a warning
  crash     killed by a signal, or a C++ exception escaping ("terminate called")
  hang      ran past the time limit
  bad_alloc a bare std::bad_alloc (a message naming no place)
  silent    exit 0, not 200 triangles, and no warning: a silent loss (or invented data)

Usage: scripts/mesh_campaign.py CLI [--seed N] [--timeout S] [--out DIR]
Every case is deterministic for a seed; the failing ones are listed by name.
"""
import argparse
import json
import os
import random
import resource
import shutil
import struct
import subprocess
import sys
import tempfile

N = 10  # grid of N x N quads: 200 triangles, 121 vertices
TRIS = 2 * N * N


def grid():
    verts = [(x * 0.1, y * 0.1, 0.01 * ((x * 7 + y * 3) % 5)) for y in range(N + 1) for x in range(N + 1)]
    tris = []
    for y in range(N):
        for x in range(N):
            a = y * (N + 1) + x
            tris += [(a, a + 1, a + N + 2), (a, a + N + 2, a + N + 1)]
    return verts, tris


def obj_text(v, t):
    return "".join("v %g %g %g\n" % p for p in v) + "".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in t)


def ply_ascii(v, t, nv=None, nf=None):
    h = "ply\nformat ascii 1.0\nelement vertex %s\nproperty float x\nproperty float y\nproperty float z\n" \
        "element face %s\nproperty list uchar int vertex_indices\nend_header\n" % (
            len(v) if nv is None else nv, len(t) if nf is None else nf)
    return h + "".join("%g %g %g\n" % p for p in v) + "".join("3 %d %d %d\n" % f for f in t)


def ply_binary(v, t, nv=None, nf=None):
    h = ("ply\nformat binary_little_endian 1.0\nelement vertex %s\nproperty float x\nproperty float y\n"
         "property float z\nelement face %s\nproperty list uchar int vertex_indices\nend_header\n" % (
             len(v) if nv is None else nv, len(t) if nf is None else nf)).encode()
    body = b"".join(struct.pack("<3f", *p) for p in v) + b"".join(struct.pack("<B3i", 3, *f) for f in t)
    return h + body


def stl_ascii(v, t):
    s = "solid grid\n"
    for a, b, c in t:
        s += "facet normal 0 0 1\n outer loop\n"
        for i in (a, b, c):
            s += "  vertex %g %g %g\n" % v[i]
        s += " endloop\nendfacet\n"
    return s + "endsolid grid\n"


def stl_binary(v, t, count=None):
    out = b"\0" * 80 + struct.pack("<I", len(t) if count is None else count)
    for a, b, c in t:
        out += struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *v[i]) for i in (a, b, c)) + b"\0\0"
    return out


def gltf_parts(v, t, index_count=None, pos_count=None, bad_index=False):
    idx = [i for f in t for i in f]
    if bad_index:
        idx[-1] = 100000
    pos = b"".join(struct.pack("<3f", *p) for p in v)
    ind = b"".join(struct.pack("<I", i) for i in idx)
    buf = pos + ind
    lo = [min(p[k] for p in v) for k in range(3)]
    hi = [max(p[k] for p in v) for k in range(3)]
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(buf)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(ind)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(v) if pos_count is None else pos_count,
                       "type": "VEC3", "min": lo, "max": hi},
                      {"bufferView": 1, "componentType": 5125,
                       "count": len(idx) if index_count is None else index_count, "type": "SCALAR"}],
    }
    return doc, buf


def glb(doc, buf, json_len=None):
    j = json.dumps(doc).encode()
    j += b" " * ((4 - len(j) % 4) % 4)
    b = buf + b"\0" * ((4 - len(buf) % 4) % 4)
    total = 12 + 8 + len(j) + 8 + len(b)
    return (b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(j) if json_len is None else json_len) +
            b"JSON" + j + struct.pack("<I", len(b)) + b"BIN\0" + b)


def gltf_files(doc, buf, name):
    doc = json.loads(json.dumps(doc))
    doc["buffers"][0]["uri"] = name + ".bin"
    return {name + ".gltf": json.dumps(doc).encode(), name + ".bin": buf}


def cases(rng):
    """(name, {file: bytes}, file to import, extra args, kind). kind 'loss' marks
    a case whose import must not come out silently short or long."""
    v, t = grid()
    base = {
        "obj": obj_text(v, t).encode(), "ply_ascii": ply_ascii(v, t).encode(), "ply_bin": ply_binary(v, t),
        "stl_ascii": stl_ascii(v, t).encode(), "stl_bin": stl_binary(v, t),
    }
    ext = {"obj": ".obj", "ply_ascii": ".ply", "ply_bin": ".ply", "stl_ascii": ".stl", "stl_bin": ".stl"}
    doc, buf = gltf_parts(v, t)
    base["glb"] = glb(doc, buf)
    ext["glb"] = ".glb"
    out = []
    for key, data in base.items():
        f = key + ext[key]
        out.append((key + "/intact", {f: data}, f, [], "loss"))
        # Cut short anywhere (past the first tenth, so some header is left).
        for i in range(24):
            at = rng.randrange(len(data) // 10, len(data) - 1)
            cut = data[:at]
            # Cutting only trailing white space leaves the same mesh.
            if data[at:].strip() == b"":
                continue
            out.append(("%s/cut@%d" % (key, at), {f: cut}, f, [], "loss"))
        # Random bytes overwritten: only crashes and hangs count here.
        for i in range(24):
            b = bytearray(data)
            for _ in range(rng.choice([1, 4, 16])):
                b[rng.randrange(len(b))] = rng.randrange(256)
            out.append(("%s/flip%d" % (key, i), {f: bytes(b)}, f, [], "flip"))
        # A block duplicated or removed in the middle.
        for i in range(6):
            a = rng.randrange(len(data) // 4, len(data) // 2)
            n = rng.randrange(1, len(data) // 8)
            mutated = data[:a] + data[a:a + n] + data[a:] if i % 2 else data[:a] + data[a + n:]
            # OBJ and ASCII STL declare no counts: whole lines or facets
            # removed or repeated make a valid, different file, so only
            # crashes and hangs count there.
            out.append(("%s/%s%d" % (key, "dup" if i % 2 else "del", i), {f: mutated}, f, [],
                        "flip" if key in ("obj", "stl_ascii") else "loss"))

    # Header counts against the data.
    for nv, nf, why in [("99999999999999999999", None, "vertex-huge"), (None, "1e9", "face-1e9"),
                        (None, 250, "face-250"), (None, 150, "face-150"), (None, 4294967295, "face-u32max"),
                        (999999999, None, "vertex-1e9"), (3, None, "vertex-3"), (None, -1, "face-neg"),
                        (None, 0, "face-0")]:
        out.append(("ply_ascii/count-" + why, {"c.ply": ply_ascii(v, t, nv, nf).encode()}, "c.ply", [], "loss"))
        out.append(("ply_bin/count-" + why, {"c.ply": ply_binary(v, t, nv, nf)}, "c.ply", [], "loss"))
    out.append(("ply/no-end_header", {"h.ply": b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"},
                "h.ply", [], "loss"))
    # ASCII PLY cut after its vertices: faces refer to vertices that are there.
    pa = ply_ascii(v, t)
    out.append(("ply_ascii/three-vertices", {"c.ply": (pa[:pa.index("end_header\n") + 11] +
                                                       "0 0 0\n1 0 0\n0 1 0\n").encode()}, "c.ply", [], "loss"))
    for count, why in [(0xFFFFFFFF, "u32max"), (250, "250"), (150, "150"), (0, "0")]:
        out.append(("stl_bin/count-" + why, {"c.stl": stl_binary(v, t, count)}, "c.stl", [], "loss"))
    sa = stl_ascii(v, t)
    out.append(("stl_ascii/20-of-200", {"c.stl": "endfacet\n".join(sa.split("endfacet\n")[:20]).encode() + b"endfacet\n"},
                "c.stl", [], "loss"))
    out.append(("glb/json-length-fffffff0", {"c.glb": glb(doc, buf, 0xFFFFFFF0)}, "c.glb", [], "loss"))
    for what, kw in [("index-out-of-range", {"bad_index": True}), ("index-count-1e9", {"index_count": 10 ** 9}),
                     ("index-count-300", {"index_count": 300}), ("pos-count-1e9", {"pos_count": 10 ** 9}),
                     ("pos-count-50", {"pos_count": 50})]:
        d, b = gltf_parts(v, t, **kw)
        out.append(("gltf/" + what, gltf_files(d, b, "g"), "g.gltf", [], "loss"))
        out.append(("glb/" + what, {"g.glb": glb(d, b)}, "g.glb", [], "loss"))
    d, b = gltf_parts(v, t)
    d2 = json.loads(json.dumps(d))
    d2["buffers"][0]["uri"] = "/dev/urandom"
    out.append(("gltf/buffer-dev-urandom", {"u.gltf": json.dumps(d2).encode()}, "u.gltf", [], "loss"))
    d2["buffers"][0]["uri"] = "dirbin"
    out.append(("gltf/buffer-directory", {"u.gltf": json.dumps(d2).encode(), "dirbin/": b""}, "u.gltf", [], "loss"))

    # OBJ faults.
    o = obj_text(v, t)
    out.append(("obj/index-out-of-range", {"o.obj": (o + "f 1 2 999\n").encode()}, "o.obj", [], "loss"))
    out.append(("obj/index-zero", {"o.obj": (o + "f 0 1 2\n").encode()}, "o.obj", [], "loss"))
    out.append(("obj/index-huge", {"o.obj": (o + "f 1 2 99999999999999999999\n").encode()}, "o.obj", [], "loss"))
    for lib, why in [("/dev/urandom", "dev-urandom"), ("/dev/zero", "dev-zero"), ("fifo.mtl", "fifo"),
                     ("dir.mtl", "directory")]:
        files = {"o.obj": ("mtllib %s\nusemtl a\n" % lib + o).encode()}
        if why == "fifo":
            files["fifo.mtl"] = "FIFO"
        if why == "directory":
            files["dir.mtl/"] = b""
        out.append(("obj/mtllib-" + why, files, "o.obj", [], "loss"))
        out.append(("obj-assimp/mtllib-" + why, dict(files), "o.obj", ["--reader", "assimp"], "loss"))
    out.append(("obj/map_Kd-dev-urandom", {"o.obj": ("mtllib m.mtl\nusemtl a\n" + o).encode(),
                                           "m.mtl": b"newmtl a\nmap_Kd /dev/urandom\n"}, "o.obj", [], "loss"))
    # Non-regular files as the mesh itself.
    out.append(("path/fifo.obj", {"p.obj": "FIFO"}, "p.obj", [], "loss"))
    out.append(("path/fifo.ply", {"p.ply": "FIFO"}, "p.ply", [], "loss"))
    out.append(("path/directory.obj", {"d.obj/": b""}, "d.obj", [], "loss"))
    out.append(("path/directory.glb", {"d.glb/": b""}, "d.glb", [], "loss"))
    out.append(("path/dev-urandom", {}, "/dev/urandom", ["--reader", "assimp"], "loss"))
    out.append(("path/dev-zero-obj", {}, "/dev/zero", ["--reader", "obj"], "loss"))

    # Numeric extremes of the import options on the intact OBJ.
    for args in [["--at", "1e300,0,0"], ["--at", "nan,0,0"], ["--at", "inf,0,0"], ["--at", "-1e7,0,0"],
                 ["--origin", "1e308,0,0"], ["--origin", "nan,nan,nan"], ["--origin", "-1e9,0,0"],
                 ["--decimate-to", "0"], ["--decimate-to", "-1"], ["--decimate-to", "1e300"],
                 ["--decimate-to", "0%"], ["--decimate-to", "1000%"], ["--decimate-to", "nan"],
                 ["--decimate-to", "99999999999999999999"], ["--max-error", "0"], ["--max-error", "-1"],
                 ["--max-error", "1e308"], ["--max-error", "nan"], ["--lods", "-1"], ["--lods", "9"],
                 ["--lods", "99999999999999999999"], ["--up", "w"], ["--reader", "ply"], ["--name", ""],
                 ["--decimate-to", "1", "--lods", "8"], ["--max-error", "0.0001", "--lods", "8"]]:
        out.append(("options/" + " ".join(args), {"o.obj": o.encode()}, "o.obj", args, "option"))
    return out


def run_case(cli, scene_template, work, case, timeout):
    name, files, target, args, kind = case
    d = tempfile.mkdtemp(dir=work)
    for f, data in files.items():
        p = os.path.join(d, f)
        if f.endswith("/"):
            os.makedirs(p, exist_ok=True)
        elif data == "FIFO":
            os.mkfifo(p)
        else:
            with open(p, "wb") as fh:
                fh.write(data)
    scene = os.path.join(d, "s.hscene")
    shutil.copy(scene_template, scene)
    path = target if target.startswith("/") else os.path.join(d, target)

    def limits():
        # 4 GB of address space per process: a reader that explodes stops there
        # instead of taking the machine.
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))

    try:
        p = subprocess.run([cli, "import", path, scene] + args, capture_output=True, timeout=timeout,
                           preexec_fn=limits, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        shutil.rmtree(d, ignore_errors=True)
        return "hang", ""
    shutil.rmtree(d, ignore_errors=True)
    err = p.stderr.decode(errors="replace")
    outp = p.stdout.decode(errors="replace")
    if p.returncode < 0 or "terminate called" in err or "Segmentation" in err:
        return "crash", err[-300:]
    if "bad_alloc" in err:
        return "bad_alloc", err[-300:]
    if p.returncode != 0:
        return "refused", err.strip().splitlines()[-1] if err.strip() else ""
    tris = None
    for word in outp.split(":", 1)[-1].split(","):
        if "triangles" in word:
            try:
                tris = int(word.split()[0])
            except ValueError:
                pass
            break
    warned = "warning" in err
    if kind == "loss" and tris != TRIS and not warned:
        return "silent", "%s triangles, no warning" % tris
    return "accepted", ("warned: " + err.strip().splitlines()[0]) if warned else ""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cli")
    ap.add_argument("--seed", type=int, default=10)
    ap.add_argument("--timeout", type=float, default=20.0)
    ap.add_argument("--out", help="write every case's outcome here as JSON")
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="hs-mesh-campaign-")
    template = os.path.join(work, "template.hscene")
    subprocess.run([a.cli, "new", template], check=True, capture_output=True)
    results = []
    counts = {}
    for case in cases(random.Random(a.seed)):
        outcome, detail = run_case(a.cli, template, work, case, a.timeout)
        counts[outcome] = counts.get(outcome, 0) + 1
        results.append({"case": case[0], "args": case[3], "outcome": outcome, "detail": detail})
        if outcome in ("crash", "hang", "bad_alloc", "silent"):
            print("%-9s %s %s  %s" % (outcome, case[0], " ".join(case[3]), detail.replace("\n", " ")[:160]))
    shutil.rmtree(work, ignore_errors=True)
    print("cases %d: %s" % (len(results), ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    if a.out:
        with open(a.out, "w") as fh:
            json.dump({"seed": a.seed, "counts": counts, "cases": results}, fh, indent=1)


if __name__ == "__main__":
    sys.exit(main())
