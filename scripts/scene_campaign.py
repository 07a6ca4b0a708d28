#!/usr/bin/env python3
"""A bounded robustness campaign against scene files and values
(docs/reliability.md, "Scene files, values, resume"; issue 10): builds a
small scene with the CLI (a sun, a camera with keys, an imported mesh whose
blob is in the file), mutates it the ways a hostile or unlucky user would,
and tries numeric extremes of every declared field and of the operations'
parameters through the CLI.

Scene file mutations (seeded):
  cut       the file truncated at a random byte (or a page boundary)
  flip      1, 4 or 16 random bytes overwritten
  sql       tables dropped, columns of the wrong type, blob keys that belong
            to nothing or that an asset names but the file lacks, blob data
            or hashes changed, the format version or description replaced
  json      the description (document.json) edited: parent cycles,
            duplicate ids, unknown references, and random members set to
            0, -1, +-1e308, NaN, Infinity, 2^63, 2^64, "", a 100 kB string,
            control characters, null, [], {}, true, or deleted

Each mutated file gets `info --json`, then `set settings.show_grid false`
(load and save), then `info` again, each with a time and memory limit:

  refused   every command refused the file with a message naming it, and
            the file's bytes are unchanged
  repaired  opened with a warning (clamped, repaired, dropped with a message)
  accepted  opened without a warning and nothing it holds was changed
            (for JSON edits: the saved file holds the edited value, and
            `set` accepts it for that field: it is within the declaration)
  crash     killed by a signal, a sanitizer report, or "terminate called"
  hang      ran past the time limit
  silent    opened without a warning, but the save holds another value
            than the file did at the edited place (or dropped it), or
            keeps a value the field's declaration refuses (a key of fov 0)
  damaged   a refused command changed the file, or the file a command
            saved no longer opens

Numeric extremes: each field `set` knows (and the operations' numeric
parameters) with 0, -1, 1e308, -1e308, nan, inf, 2^63 and "" on a fresh
copy of the scene, sorted the same way: refused (exit 1 or 2, the field or
option named, file unchanged), accepted (the file holds the value given, or
for an operation a value its declaration allows), repaired (another value
and a warning), silent (another value, or a value the declaration does not
allow, and no warning), crash, hang, damaged (the file no longer opens).

Usage: scripts/scene_campaign.py CLI [--seed N] [--timeout S] [--out FILE]
       [--only scene|values]
Every case is deterministic for a seed; the failing ones are listed by name.
"""
import argparse
import copy
import json
import math
import os
import random
import resource
import shutil
import sqlite3
import subprocess
import sys
import tempfile

BAD_OUTCOMES = ("crash", "hang", "silent", "damaged")


def limits():
    # 4 GB of address space: a command that explodes stops there instead of
    # taking the machine. No core files.
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def run(cli, args, cwd, timeout):
    """(returncode or 'hang', stdout, stderr)."""
    try:
        p = subprocess.run([cli] + args, cwd=cwd, capture_output=True, timeout=timeout, preexec_fn=limits,
                           stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "hang", "", ""
    return p.returncode, p.stdout.decode(errors="replace"), p.stderr.decode(errors="replace")


def crashed(code, err):
    return code != "hang" and (code < 0 or "terminate called" in err or "Sanitizer" in err or
                               "runtime error:" in err or "Segmentation" in err)


def read_bytes(path):
    try:
        with open(path, "rb") as fh:
            return fh.read()
    except OSError:
        return None


def description(path):
    """The scene description (parsed) of a scene file, or None."""
    try:
        db = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
        row = db.execute("SELECT json FROM document WHERE id = 1").fetchone()
        db.close()
        return json.loads(row[0]) if row else None
    except Exception:
        return None


def write_description(path, doc_text):
    db = sqlite3.connect(path)
    db.execute("UPDATE document SET json = ? WHERE id = 1", (doc_text,))
    db.commit()
    db.close()


# ---- the scene ------------------------------------------------------------------------------


def grid_obj(n=4):
    v = [(x * 0.1, y * 0.1, 0.01 * ((x * 7 + y * 3) % 5)) for y in range(n + 1) for x in range(n + 1)]
    s = "".join("v %g %g %g\n" % p for p in v)
    for y in range(n):
        for x in range(n):
            a = y * (n + 1) + x + 1
            s += "f %d %d %d\nf %d %d %d\n" % (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1)
    return s


def make_template(cli, work, timeout):
    path = os.path.join(work, "template.hscene")
    with open(os.path.join(work, "grid.obj"), "w") as fh:
        fh.write(grid_obj())
    for args in (["new", path], ["import", "grid.obj", path, "--name", "Grid"],
                 ["key", "Camera", "camera.fov_deg", "0", "40", path],
                 ["key", "Camera", "camera.fov_deg", "120f", "60", path],
                 ["key", "Camera", "transform.translation", "60f", "1,2,3", path],
                 ["key", "Sun", "light.intensity", "30f", "3", path]):
        code, out, err = run(cli, args, work, timeout)
        if code != 0:
            sys.exit("building the campaign's scene failed: %s: %s" % (" ".join(args), err))
    return path


# ---- scene file mutations -------------------------------------------------------------------

HOSTILE = [0, -1, 1e308, -1e308, float("nan"), float("inf"), float("-inf"), 2 ** 63, 2 ** 64, "", "x" * 100000,
           "\r\x1b[2J\x07", None, [], {}, True, -0.0, 1e-308]


def leaves(node, path=()):
    """Every member path of a JSON tree (objects and arrays, and their leaves)."""
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            out.append(path + (k,))
            out += leaves(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append(path + (i,))
            out += leaves(v, path + (i,))
    return out


def get_at(node, path):
    for p in path:
        node = node[p]
    return node


def set_at(node, path, value):
    get_at(node, path[:-1])[path[-1]] = value


def json_cases(doc, rng, count):
    """Structural edits, then `count` random ones: (name, edited doc, path or None, deleted)."""
    out = []
    ents = {e["name"]: e for e in doc["entities"]}
    cam, sun, grid = ents["Camera"], ents["Sun"], ents["Grid"]

    def edit(name, fn, path=None, deleted=False):
        d = copy.deepcopy(doc)
        fn(d, {e["name"]: e for e in d["entities"]})
        out.append((name, d, path, deleted))

    def cycle(d, e):
        e["Camera"]["parent"], e["Camera"]["children"] = e["Grid"]["id"], [e["Grid"]["id"]]
        e["Grid"]["parent"], e["Grid"]["children"] = e["Camera"]["id"], [e["Camera"]["id"]]
        d["roots"] = [e["Sun"]["id"]]

    def self_parent(d, e):
        e["Grid"]["parent"], e["Grid"]["children"] = e["Grid"]["id"], [e["Grid"]["id"]]

    def child_not_listed(d, e):
        e["Grid"]["parent"] = e["Camera"]["id"]

    def dup_entity(d, e):
        e["Grid"]["id"] = e["Camera"]["id"]

    def dup_asset(d, e):
        d["assets"].append(copy.deepcopy(d["assets"][0]))

    def unknown_root(d, e):
        d["roots"].append(99)

    def root_missing(d, e):
        d["roots"] = d["roots"][:1]

    def unknown_asset(d, e):
        e["Grid"]["components"]["mesh"]["asset"] = 99

    def asset_hash(d, e):
        d["assets"][0]["hash"] = "0123456789abcdef"

    def unknown_binding(d, e):
        d["sequence"]["bindings"][0]["entity"] = 99

    def unknown_property(d, e):
        d["sequence"]["bindings"][0]["tracks"][0]["property"] = "camera.warp_factor"

    def key_time(value):
        return lambda d, e: d["sequence"]["bindings"][0]["tracks"][0]["keys"][0].__setitem__("t", value)

    def version(value):
        return lambda d, e: d.__setitem__("version", value)

    edit("json/parent-cycle", cycle)
    edit("json/self-parent", self_parent)
    edit("json/child-not-listed", child_not_listed)
    edit("json/duplicate-entity-id", dup_entity)
    edit("json/duplicate-asset-id", dup_asset)
    edit("json/unknown-root", unknown_root)
    edit("json/root-missing", root_missing)
    edit("json/unknown-asset", unknown_asset)
    edit("json/asset-hash-changed", asset_hash)
    edit("json/binding-unknown-entity", unknown_binding)
    edit("json/track-unknown-property", unknown_property)
    for v in (float("nan"), 1e308, -1e308, 2 ** 63):
        edit("json/key-time-%r" % v, key_time(v))
    for v in (999999999999999999999, -1, 0, "5"):
        edit("json/version-%r" % v, version(v))
    edit("json/format-wrong", lambda d, e: d.__setitem__("format", "something-else"))

    # Keyed values outside their fields' declarations (issue 10, item 5).
    def key_value(prop, value):
        def f(d, e):
            for b in d["sequence"]["bindings"]:
                for t in b["tracks"]:
                    if t["property"] == prop:
                        t["keys"][0]["v"] = value
        return f

    for prop, value in (("camera.fov_deg", 0), ("camera.fov_deg", 1e308), ("camera.fov_deg", -1),
                        ("light.intensity", -1), ("light.intensity", 1e308), ("transform.translation", [1e308] * 3)):
        where = [("sequence", "bindings", bi, "tracks", ti, "keys", 0, "v")
                 for bi, b in enumerate(doc["sequence"]["bindings"]) for ti, t in enumerate(b["tracks"])
                 if t["property"] == prop]
        edit("json/key-value %s=%r" % (prop, value), key_value(prop, value), where[0])
    for i in range(count):
        paths = [p for p in leaves(doc) if p[0] not in ("format", "version")]
        path = rng.choice(paths)
        if rng.random() < 0.12:
            d = copy.deepcopy(doc)
            parent = get_at(d, path[:-1])
            del parent[path[-1]]
            out.append(("json/delete %s" % "/".join(map(str, path)), d, path, True))
            continue
        value = rng.choice(HOSTILE)
        d = copy.deepcopy(doc)
        set_at(d, path, value)
        shown = repr(value) if not (isinstance(value, str) and len(value) > 20) else "'x'*%d" % len(value)
        out.append(("json/%s=%s" % ("/".join(map(str, path)), shown), d, path, False))
    return out


def sql_cases():
    """(name, statements) run on a copy of the scene."""
    c = []

    def add(name, *st):
        c.append(("sql/" + name, st))

    add("drop-document", "DROP TABLE document")
    add("drop-blobs", "DROP TABLE blobs")
    add("drop-meta", "DROP TABLE meta")
    add("drop-all", "DROP TABLE document", "DROP TABLE blobs", "DROP TABLE meta")
    add("document-json-blob", "ALTER TABLE document RENAME TO d0",
        "CREATE TABLE document(id INTEGER PRIMARY KEY, json BLOB NOT NULL)",
        "INSERT INTO document SELECT id, CAST(json AS BLOB) FROM d0", "DROP TABLE d0")
    add("document-json-integer", "ALTER TABLE document RENAME TO d0",
        "CREATE TABLE document(id INTEGER PRIMARY KEY, json INTEGER)", "INSERT INTO document VALUES (1, 42)",
        "DROP TABLE d0")
    add("document-no-json-column", "ALTER TABLE document RENAME TO d0",
        "CREATE TABLE document(id INTEGER PRIMARY KEY, text TEXT)", "INSERT INTO document SELECT * FROM d0",
        "DROP TABLE d0")
    add("blobs-data-text", "ALTER TABLE blobs RENAME TO b0",
        "CREATE TABLE blobs(key TEXT NOT NULL, part INTEGER NOT NULL, hash TEXT NOT NULL, data TEXT NOT NULL, "
        "PRIMARY KEY(key, part))", "INSERT INTO blobs SELECT * FROM b0", "DROP TABLE b0")
    add("blobs-part-text", "ALTER TABLE blobs RENAME TO b0",
        "CREATE TABLE blobs(key TEXT NOT NULL, part TEXT NOT NULL, hash TEXT NOT NULL, data BLOB NOT NULL, "
        "PRIMARY KEY(key, part))", "INSERT INTO blobs SELECT key, 'zero', hash, data FROM b0", "DROP TABLE b0")
    add("blobs-no-hash", "ALTER TABLE blobs RENAME TO b0",
        "CREATE TABLE blobs(key TEXT NOT NULL, part INTEGER NOT NULL, data BLOB NOT NULL, PRIMARY KEY(key, part))",
        "INSERT INTO blobs SELECT key, part, data FROM b0", "DROP TABLE b0")
    add("blob-data-integer", "UPDATE blobs SET data = 12345")
    add("blob-data-null-text", "UPDATE blobs SET data = ''")
    add("blob-dangling-key", "INSERT INTO blobs VALUES ('mesh/99', 0, '0123456789abcdef', x'00010203')")
    add("blob-foreign-key", "INSERT INTO blobs VALUES ('../../etc/passwd', 0, '00', x'00')")
    add("blob-missing", "DELETE FROM blobs")
    add("blob-renamed", "UPDATE blobs SET key = 'mesh/7'")
    add("blob-hash-changed", "UPDATE blobs SET hash = '0123456789abcdef'")
    add("blob-hash-not-hex", "UPDATE blobs SET hash = 'zz'")
    add("blob-truncated", "UPDATE blobs SET data = substr(data, 1, length(data) / 2)")
    add("blob-one-byte", "UPDATE blobs SET data = substr(data, 1, 1)")
    add("blob-random", "UPDATE blobs SET data = randomblob(length(data))")
    add("blob-huge-zero", "UPDATE blobs SET data = zeroblob(50000000)")
    add("blob-extra-part", "INSERT INTO blobs SELECT key, part + 1, hash, data FROM blobs")
    add("blob-part-negative", "UPDATE blobs SET part = -1")
    add("blob-part-huge", "UPDATE blobs SET part = 9223372036854775807")
    for v in ("999999999999999999999", "-1", "0", "6", "x", ""):
        add("meta-format-version-%s" % (v or "empty"), "UPDATE meta SET value = '%s' WHERE key = 'format_version'" % v)
    add("meta-format-other", "UPDATE meta SET value = 'sqlite-something' WHERE key = 'format'")
    add("meta-rows-gone", "DELETE FROM meta")
    add("document-row-gone", "DELETE FROM document")
    add("document-two-rows", "ALTER TABLE document RENAME TO d0",
        "CREATE TABLE document(id INTEGER PRIMARY KEY, json TEXT NOT NULL)",
        "INSERT INTO document SELECT * FROM d0", "INSERT INTO document SELECT 2, json FROM d0", "DROP TABLE d0")
    for name, text in (("empty", ""), ("array", "[]"), ("null", "null"), ("object", "{}"), ("number", "1e999"),
                       ("not-json", "{\"format\": \"hybridscape-scene\", "), ("deep", "[" * 100000 + "]" * 100000),
                       ("control", "\r\x1b[2J")):
        c.append(("sql/document-json-" + name, ("UPDATE document SET json = ?",), text))
    add("extra-table", "CREATE TABLE extra(x)")
    add("page-size-vacuum", "PRAGMA page_size = 512", "VACUUM")
    return c


def scene_cases(template, rng, json_count):
    data = read_bytes(template)
    doc = description(template)
    out = []
    # Cut short: random bytes, and some page boundaries.
    pages = [n for n in range(512, len(data), 4096)]
    for i in range(24):
        out.append(("cut@%d", "cut", rng.randrange(16, len(data) - 1)))
    for at in pages[:6]:
        out.append(("cut@%d", "cut", at))
    for i in range(40):
        n = rng.choice([1, 4, 16])
        where = [(rng.randrange(len(data)), rng.randrange(256)) for _ in range(n)]
        out.append(("flip%d" % i, "flip", where))
    for name, st, *arg in sql_cases():
        out.append((name, "sql", (st, arg[0] if arg else None)))
    for name, d, path, deleted in json_cases(doc, rng, json_count):
        out.append((name, "json", (d, path, deleted)))
    return out


def prepare(case, template, scene):
    name, kind, arg = case
    data = read_bytes(template)
    if kind == "cut":
        with open(scene, "wb") as fh:
            fh.write(data[:arg])
        return name % arg
    if kind == "flip":
        b = bytearray(data)
        for at, value in arg:
            b[at] = value
        with open(scene, "wb") as fh:
            fh.write(bytes(b))
        return name
    shutil.copy(template, scene)
    if kind == "sql":
        statements, param = arg
        db = sqlite3.connect(scene)
        for st in statements:
            if param is not None:
                db.execute(st, (param,))
            else:
                db.execute(st)
        db.commit()
        db.close()
        return name
    d, path, deleted = arg
    write_description(scene, json.dumps(d, indent=1))
    return name


def same_json(a, b):
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b or a == b and type(a) == type(b)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if math.isnan(a) or math.isnan(b):
            return False
        if a == b:
            return True
        return abs(a - b) <= 1e-6 * max(abs(a), abs(b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_json(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same_json(x, y) for x, y in zip(a, b))
    return a == b


def field_at(doc, path):
    """The `set` field and entity a description path holds a value of, or None:
    (entity name or None for settings, "component.key", path of the whole value)."""
    p = list(path)
    if p[0] == "settings" and len(p) >= 2:
        return None, "settings." + p[1], tuple(p[:2])
    if p[0] == "entities" and len(p) >= 3 and isinstance(p[1], int) and p[1] < len(doc["entities"]):
        name = doc["entities"][p[1]]["name"]
        if p[2] == "name":
            return name, "entity.name", tuple(p[:3])
        if p[2] == "transform" and len(p) >= 4 and p[3] in ("translation", "scale"):
            return name, "transform." + p[3], tuple(p[:4])
        if p[2] == "components" and len(p) >= 5:
            return name, "%s.%s" % (p[3], p[4]), tuple(p[:5])
    if p[0] == "sequence" and len(p) >= 8 and p[1] == "bindings" and p[3] == "tracks" and p[5] == "keys" and \
            p[7] == "v":
        binding = doc["sequence"]["bindings"][p[2]]
        track = binding["tracks"][p[4]]
        names = {e["id"]: e["name"] for e in doc["entities"]}
        if binding["entity"] in names and track["property"] != "transform.rotation":
            return names[binding["entity"]], track["property"], tuple(p[:8])
    return None


def as_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list):
        return ",".join(as_text(v) for v in value)
    return value if isinstance(value, str) else repr(value)


def declared_valid(cli, template, work, doc, edited, path, timeout):
    """Whether the edited value is one `set` (the fields' declarations)
    accepts; None where the path is no field `set` knows."""
    if len(path) >= 8 and path[0] == "sequence" and path[-1] == "t":
        t = get_at(edited, path)
        return isinstance(t, (int, float)) and math.isfinite(t) and abs(t * 60) <= 2 ** 31 - 1
    where = field_at(doc, path)
    if where is None:
        return None
    entity, field, whole = where
    try:
        value = get_at(edited, whole)
    except (KeyError, IndexError, TypeError):
        return None
    if not isinstance(value, (int, float, str, list)) or (isinstance(value, list) and len(value) != 3):
        return None
    d = tempfile.mkdtemp(dir=work)
    try:
        scene = os.path.join(d, "v.hscene")
        shutil.copy(template, scene)
        args = ["set", field, as_text(value), scene] if entity is None else ["set", entity, field, as_text(value), scene]
        code, out, err = run(cli, args, d, timeout)
        return code == 0
    finally:
        shutil.rmtree(d, ignore_errors=True)


def run_scene_case(cli, template, work, case, timeout):
    d = tempfile.mkdtemp(dir=work)
    scene = os.path.join(d, "s.hscene")
    name = prepare(case, template, scene)
    before = read_bytes(scene)
    name_in_msg = "s.hscene"
    try:
        c1, o1, e1 = run(cli, ["info", "--json", scene], d, timeout)
        if c1 == "hang":
            return name, "hang", "info"
        if crashed(c1, e1):
            return name, "crash", "info: " + e1[-300:]
        c2, o2, e2 = run(cli, ["set", "settings.show_grid", "false", scene], d, timeout)
        if c2 == "hang":
            return name, "hang", "set"
        if crashed(c2, e2):
            return name, "crash", "set: " + e2[-300:]
        if c2 != 0:
            if read_bytes(scene) != before:
                return name, "damaged", "set refused it and changed the file: " + e2.strip()[-200:]
            if c1 != 0:
                last = (e1.strip().splitlines() or [""])[-1]
                return name, "refused" if name_in_msg in e1 else "refused-unnamed", last[:200]
            # info read it, set could not: still a refusal of the change.
            last = (e2.strip().splitlines() or [""])[-1]
            return name, "refused" if name_in_msg in e2 else "refused-unnamed", "set: " + last[:200]
        c3, o3, e3 = run(cli, ["info", scene], d, timeout)
        if c3 == "hang" or crashed(c3, e3):
            return name, "hang" if c3 == "hang" else "crash", "info after save: " + e3[-300:]
        if c3 != 0:
            return name, "damaged", "the saved file no longer opens: " + e3.strip()[-200:]
        warned = "warning" in e1 or "warning" in e2
        if warned:
            lines = [l for l in (e1 + e2).splitlines() if "warning" in l]
            return name, "repaired", lines[0][:200]
        if case[1] == "json":
            edited, path, deleted = case[2]
            saved = description(scene)
            # A member emptied ({}) reads like one an older build did not
            # write: its defaults, by design, like a deleted member.
            try:
                emptied = path is not None and not deleted and get_at(edited, path) == {}
            except (KeyError, IndexError, TypeError):
                emptied = False
            if path is not None and not deleted and not emptied and saved is not None:
                try:
                    want = get_at(edited, path)
                    have = get_at(saved, path)
                except (KeyError, IndexError, TypeError):
                    return name, "silent", "the edited member is gone from the saved file"
                if path[-1] != "show_grid" and not same_json(want, have):
                    return name, "silent", "saved %s" % json.dumps(have)[:100]
                # Kept as edited: silent if the field's declaration refuses it.
                if c1 == 0 and declared_valid(cli, template, work, description(template), edited, path,
                                              timeout) is False:
                    return name, "silent", "kept a value its field's declaration refuses: %s" % \
                        json.dumps(get_at(edited, path))[:80]
        if c1 != 0:
            return name, "refused", (e1.strip().splitlines() or [""])[-1][:200]
        return name, "accepted", ""
    finally:
        shutil.rmtree(d, ignore_errors=True)


# ---- numeric extremes -----------------------------------------------------------------------

EXTREMES = ["0", "-1", "1e308", "-1e308", "nan", "inf", "9223372036854775808", ""]


def field_cases(cli, work, timeout):
    code, out, err = run(cli, ["set", "--help"], work, timeout)
    fields = [l.split()[0] for l in out.splitlines() if l.startswith("  ") and "." in l.split()[0] and "(" in l]
    owner = {"entity": "Camera", "transform": "Camera", "camera": "Camera", "light": "Sun", "mesh": "Grid"}
    out_cases = []
    for f in fields:
        comp = f.split(".")[0]
        if comp != "settings" and comp not in owner:
            continue  # a component the scene has no entity with (terrain)
        for v in EXTREMES:
            value = v
            if f in ("transform.translation", "transform.rotation_deg", "transform.scale", "light.color",
                     "mesh.tint", "settings.sky_zenith", "settings.sky_horizon", "settings.ground_color"):
                value = ",".join([v] * 3)
            args = ["set", f, value] if comp == "settings" else ["set", owner[comp], f, value]
            out_cases.append(("set %s %r" % (f, value), args, f, v))
    return out_cases


def op_cases():
    """(name, args with {S} for the scene, option, value, allowed(value) -> bool)."""
    c = []
    rng = lambda lo, hi: (lambda x: x is not None and lo <= x <= hi)
    for v in EXTREMES:
        c.append(("render --quality %r" % v, ["render", "{S}", "--out", "o.jpg", "--size", "16x16", "--quality", v],
                  "--quality", v, rng(1, 100)))
        c.append(("render --size %r" % v, ["render", "{S}", "--out", "o.png", "--size", "%sx%s" % (v, v)],
                  "--size", v, rng(1, 16384)))
        c.append(("key time %r" % v, ["key", "Camera", "camera.fov_deg", v, "40", "{S}"], "time", v,
                  rng(-2147483647 / 60, 2147483647 / 60)))
        c.append(("key frame %r" % v, ["key", "Camera", "camera.fov_deg", v + "f", "40", "{S}"], "time", v,
                  rng(-2147483647, 2147483647)))
        c.append(("sequence --fps %r" % v, ["sequence", "{S}", "--fps", v], "--fps", v, rng(1e-3, 1000)))
        c.append(("sequence --range %r" % v, ["sequence", "{S}", "--range", "%s-%s" % (v, v)], "--range", v,
                  rng(-2147483647, 2147483647)))
        c.append(("import --at %r" % v, ["import", "grid.obj", "{S}", "--at", ",".join([v] * 3)], "--at", v,
                  rng(-1e7, 1e7)))
        c.append(("import --max-error %r" % v, ["import", "grid.obj", "{S}", "--max-error", v], "--max-error", v,
                  rng(1e-4, 1000)))
    return c


def number(text):
    try:
        x = float(text)
    except ValueError:
        return None
    return x if math.isfinite(x) else None


def stored_value(doc, field):
    comp, key = field.split(".", 1)
    if comp == "settings":
        return doc["settings"].get(key, KeyError)
    ent = {"entity": "Camera", "transform": "Camera", "camera": "Camera", "light": "Sun", "mesh": "Grid"}[comp]
    e = next((x for x in doc["entities"] if x["name"] == ent), None)
    if e is None:
        return KeyError
    if comp == "entity":
        return e.get(key, KeyError)
    if comp == "transform":
        return e["transform"].get(key, KeyError)
    return e["components"].get(comp, {}).get(key, KeyError)


def run_value_case(cli, template, work, case, timeout, is_field):
    d = tempfile.mkdtemp(dir=work)
    scene = os.path.join(d, "s.hscene")
    shutil.copy(template, scene)
    with open(os.path.join(d, "grid.obj"), "w") as fh:
        fh.write(grid_obj())
    before = read_bytes(scene)
    try:
        if is_field:
            name, args, field, v = case
            args = args + [scene]
            named = field.split(".", 1)[1] if field.startswith("settings.") else field
        else:
            name, args, option, v, allowed = case
            args = [scene if a == "{S}" else a for a in args]
            named = option
        code, out, err = run(cli, args, d, timeout)
        if code == "hang":
            return name, "hang", ""
        if crashed(code, err):
            return name, "crash", err[-300:]
        c2, o2, e2 = run(cli, ["info", scene], d, timeout)
        if c2 == "hang" or crashed(c2, e2) or c2 != 0:
            return name, "damaged", "the file no longer opens: " + e2.strip()[-200:]
        warned = "warning" in err
        if code != 0:
            if read_bytes(scene) != before:
                return name, "damaged", "refused, but the file changed"
            last = (err.strip().splitlines() or [""])[-1]
            return name, "refused" if named.split(".")[-1] in err or named in err else "refused-unnamed", last[:160]
        if not is_field:
            x = number(v)
            if allowed(x):
                return name, "accepted", ""
            return name, "repaired" if warned else "silent", "exit 0 with %r: %s" % (v, (out + err).strip()[-160:])
        # A field: the file holds the value given, or says why not.
        doc = description(scene)
        have = stored_value(doc, field) if doc else KeyError
        if have is KeyError or field in ("transform.rotation_deg", "camera.focal_length_mm"):
            return name, "accepted", "(value not compared: not stored as given)"
        x = number(v)
        want = [x] * 3 if isinstance(have, list) else x
        if x is not None and same_json(want, have):
            return name, "accepted", ""
        if isinstance(have, str) and v == have:
            return name, "accepted", ""
        if isinstance(have, bool) and v in ("0", "1") and have == (v == "1"):
            return name, "accepted", ""  # 0 and 1 are off and on
        if isinstance(have, str) and v.isdigit() and field not in ("entity.name",):
            return name, "accepted", ""  # an enum value given by its index
        return name, "repaired" if warned else "silent", "stored %s for %r" % (json.dumps(have)[:80], v)
    finally:
        shutil.rmtree(d, ignore_errors=True)


# ---- main -----------------------------------------------------------------------------------


def table(title, results):
    counts = {}
    for r in results:
        counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
    print("%s: %d cases: %s" % (title, len(results), ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    return counts


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cli")
    ap.add_argument("--seed", type=int, default=10)
    ap.add_argument("--timeout", type=float, default=20.0)
    ap.add_argument("--json-edits", type=int, default=85, help="random edits of the description (default 85)")
    ap.add_argument("--only", choices=["scene", "values"])
    ap.add_argument("--out", help="write every case's outcome here as JSON")
    a = ap.parse_args()
    cli = os.path.abspath(a.cli)
    work = tempfile.mkdtemp(prefix="hs-scene-campaign-")
    rng = random.Random(a.seed)
    report = {"seed": a.seed}
    try:
        template = make_template(cli, work, a.timeout)
        if a.only != "values":
            results = []
            for case in scene_cases(template, rng, a.json_edits):
                name, outcome, detail = run_scene_case(cli, template, work, case, a.timeout)
                results.append({"case": name, "outcome": outcome, "detail": detail})
                if outcome in BAD_OUTCOMES or outcome == "refused-unnamed":
                    print("%-9s %s  %s" % (outcome, name[:90], detail.replace("\n", " ")[:200]))
            report["scene"] = {"counts": table("scene files", results), "cases": results}
        if a.only != "scene":
            results = []
            for case in field_cases(cli, work, a.timeout):
                name, outcome, detail = run_value_case(cli, template, work, case, a.timeout, True)
                results.append({"case": name, "outcome": outcome, "detail": detail})
                if outcome in BAD_OUTCOMES or outcome == "refused-unnamed":
                    print("%-9s %s  %s" % (outcome, name, detail.replace("\n", " ")[:200]))
            for case in op_cases():
                name, outcome, detail = run_value_case(cli, template, work, case, a.timeout, False)
                results.append({"case": name, "outcome": outcome, "detail": detail})
                if outcome in BAD_OUTCOMES or outcome == "refused-unnamed":
                    print("%-9s %s  %s" % (outcome, name, detail.replace("\n", " ")[:200]))
            report["values"] = {"counts": table("numeric extremes", results), "cases": results}
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if a.out:
        with open(a.out, "w") as fh:
            json.dump(report, fh, indent=1)
    bad = sum(r["outcome"] in BAD_OUTCOMES for part in ("scene", "values") if part in report
              for r in report[part]["cases"])
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
