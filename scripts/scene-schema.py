#!/usr/bin/python3
"""Writes the settings' part of docs/scene.schema.json from the settings registry
(`fresnel settings --json`, libs/job/src/settings.cpp), or with --check fails when the schema
has drifted from it.

Every setting scene files hold is a property at its key's place (camera.yaw is
/camera/yaw: $defs.camera.properties.yaw), with its description, type, range and choices.
A model's material overrides ($defs.materialOverride) hold the material property registry's
properties (`fresnel settings --materials --json`, libs/material/src/properties.cpp).
Properties the schema gives as a reference ($ref: the environment and background objects,
the lookAt camera's target) are structures, written by hand.

usage: scripts/scene-schema.py FRESNEL_BINARY [--check]
"""
import json
import subprocess
import sys
from pathlib import Path

root = Path(__file__).resolve().parent.parent
page = root / "docs" / "scene.schema.json"


def schema_of(s):
    t = s["type"]
    if t == "bool":
        out = {"type": "boolean"}
    elif t in ("int", "number"):
        out = {"type": "integer" if t == "int" else "number", "minimum": s["min"], "maximum": s["max"]}
    elif t == "vec3":
        item = {"type": "number", "minimum": s["min"], "maximum": s["max"]}
        out = {"type": "array", "items": item, "minItems": 3, "maxItems": 3}
    elif t == "size":
        side = {"type": "integer", "minimum": int(s["min"]), "maximum": int(s["max"])}
        out = {"oneOf": [{"type": "array", "items": side, "minItems": 2, "maxItems": 2},
                         {"type": "string", "pattern": "^[0-9]+x[0-9]+$"}]}
    elif t == "choice":
        out = {"enum": s["choices"]}
    else:
        out = {"type": "string"}
    for k in ("minimum", "maximum"):  # whole numbers as integers in the file
        if k in out and float(out[k]).is_integer():
            out[k] = int(out[k])
    if s["none"]:
        out = {"anyOf": [out, {"const": s["none"]}]}
    flag = f" (render {s['flag']})" if s["flag"] else ""
    default = f" Default: {s['default']}." if s["default"] else ""
    return {"description": s["doc"] + "." + default + flag, **out}


def material_schema_of(p):
    def bounded(out):
        for k, v in (("minimum", p["min"]), ("maximum", p["max"])):
            if v is not None:
                out[k] = int(v) if float(v).is_integer() else v
        return out
    if p["type"] == "bool":
        out = {"type": "boolean"}
    elif p["type"] == "choice":
        out = {"enum": p["choices"]}
    elif p["width"] == 1:
        out = bounded({"type": "number"})
    else:
        out = {"type": "array", "items": bounded({"type": "number"}), "minItems": p["width"], "maxItems": p["width"]}
    block = f" ({p['block']})" if p["block"] else ""
    return {"description": f"{p['doc']}{block}. Default: {p['default']}.", **out}


def container(schema, parts):
    """The object schema holding the properties of the key prefix `parts`."""
    node = schema
    for part in parts:
        node = node["properties"][part]
        if "$ref" in node:
            node = schema["$defs"][node["$ref"].split("/")[-1]]
        if "oneOf" in node:
            node = next(o for o in node["oneOf"] if o.get("type") == "object")
    return node


def main():
    binary, mode = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "write")
    registry = json.loads(subprocess.run([binary, "settings", "--json"], check=True, capture_output=True,
                                         text=True).stdout)
    old_text = page.read_text()
    schema = json.loads(old_text)
    written = []
    for s in registry:
        if "sceneFile" not in s["frontEnds"]:
            continue
        parts = s["key"].split(".")
        props = container(schema, parts[:-1]).setdefault("properties", {})
        if "$ref" in props.get(parts[-1], {}):
            continue  # a structure, by hand
        props[parts[-1]] = schema_of(s)
        written.append(s["key"])
    materials = json.loads(subprocess.run([binary, "settings", "--materials", "--json"], check=True,
                                          capture_output=True, text=True).stdout)
    override = schema["$defs"]["materialOverride"]["properties"]
    for key in [k for k in override if k not in ("name", "index")]:
        del override[key]
    for p in materials["properties"]:
        override[p["name"]] = material_schema_of(p)
        written.append("materials." + p["name"])
    new_text = json.dumps(schema, indent=2, ensure_ascii=False) + "\n"
    if mode == "--check":
        if new_text != old_text:
            print("docs/scene.schema.json has drifted from the settings registry: run scripts/scene-schema.py "
                  "build/bin/fresnel")
            import difflib
            sys.stdout.writelines(list(difflib.unified_diff(old_text.splitlines(True), new_text.splitlines(True)))[:60])
            return 1
        print(f"docs/scene.schema.json holds the registries' {len(written)} scene-file settings and material properties")
        return 0
    page.write_text(new_text)
    print(f"wrote {len(written)} settings into docs/scene.schema.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
