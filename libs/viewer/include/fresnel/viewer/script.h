#pragma once
// `fresnel view --script FILE`: one command per line, run in order by the viewer (for
// tests and for people). Blank lines and lines starting with # are skipped.
//   orbit DYAW DPITCH      turn the orbit camera (degrees)
//   pan DX DY              move the target as a drag of DX, DY pixels would
//   dolly FACTOR           distance K *= FACTOR
//   reset | frame          R and F: the initial camera; the bounds' centre and fit distance
//   camera N | orbit       the file's N-th camera; the orbit camera
//   open PATH              a model or a scene file (a broken file: reported, the current scene stays)
//   env PATH|studio|none|color:R,G,B   the environment (a broken file: reported, the current one stays)
//   set KEY VALUE          a job setting by its key (fresnel/job/settings.h; `fresnel settings`
//                          lists them): set render.exposure 1, set camera.fov 30, set background blur.
//                          VALUE is the rest of the line; set environment FILE is env FILE
//   env-rotation DEG | env-intensity X | exposure EV | tonemap NAME | debug CHANNEL | background B
//                          older spellings of set environment.rotation, environment.intensity,
//                          render.exposure, render.toneMapping, render.debug, background (a warning)
//   wait FRAMES            let FRAMES frames pass
//   screenshot PATH        write the frame (as --screenshot) once the lighting is ready
//   print                  print the `fresnel render` command line of the view
//   set material INDEX NAME VALUE...    a property of material INDEX from the material property
//                          registry (fresnel/material/properties.h; `fresnel settings` lists them):
//                          baseColorFactor 1 0 0 1, roughnessFactor 0.3, alphaMode MASK, ... A
//                          missing extension block is added with its defaults (live; save writes
//                          them into the glTF file, save-scene as material overrides)
//   save PATH              the material edits written into a copy of the model's glTF file (or the
//                          file itself), keeping everything else byte for byte (scene_writer.h)
//   save-scene PATH        the view as a scene file (*.fresnel.json) that `fresnel render PATH` renders
//   auto-rotate camera|env on|off   turn the camera or the environment, 30 degrees a second
//   reload-shaders [DIR]   F5: read the shader files again (from DIR, else --shaders) and recompile;
//                          a compile error is reported and the shaders in use stay
//   split CHANNEL POS | split off   the split view: right of POS (0..1 of the width) the debug CHANNEL (or none)
//   light SPEC             add a light, SPEC as render --light (dir:..., point:..., spot:...)
//   light-remove N         remove the N-th added light
//   orbit-lights on|off    turn the added lights about the model (+Y), 30 degrees a second
//   hide NODE | show NODE  the node's visibility (KHR_node_visibility: its subtree's meshes and lights)
//   select NODE            select the node's first primitive (as a click on it; the material editor follows)
//   pick X Y               click-select at window point X, Y (from the top left); prints one JSON
//                          line: {"node":N,"mesh":M,"primitive":P,"material":K,"distance":D} or {"node":null}
//   play | pause           animation playback (from the time shown; play at the end starts again)
//   time T                 show time T (seconds) of the animations: the scene posed as render --time T
//   animation N|all        play only animation N, or all of them (render --animation)
//   speed X | loop on|off  playback speed (seconds of animation a second; negative: backwards), looping
//   stats                  print frame time, draw calls, triangles and resident memory as one JSON line
//   quit                   exit: 0, or 1 when an open/env/screenshot of the script failed
// Paths are relative to the current folder. A malformed line is reported as FILE:LINE and
// the viewer exits 1 before opening its window.
#include <cstddef>
#include <string>
#include <vector>

#include "fresnel/material/material.h"

namespace fresnel::viewer {

// One checked line of a script (what Automation runs).
struct Command {
    int line = 0;
    std::string name;
    std::vector<std::string> args;
    float number(std::size_t i) const;  // args[i] as a number (checked when the script was read)
};

// Sets a `set material` field (a material property registry name) from the numbers the reader
// left (a choice as its index, a boolean as 0/1); false when the name or the values are not one.
bool set_material_field(Material& m, const std::string& field, const std::vector<float>& values);

// The setting an older command of the script stands for (exposure: render.exposure), or null.
const char* shorthand_key(const std::string& command);

// Reads and checks `path`. Throws fresnel::Error (file: the script, where: "line N").
std::vector<Command> read_view_script(const std::string& path);

}  // namespace fresnel::viewer
