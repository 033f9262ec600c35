// invfree's public header: what an embedding program includes to build a scene, step it
// and read the state back. The solver's pieces (core/solver, core/potential, core/linalg)
// stay behind `step`.
//
//   invfree::SceneDef scene;  // the defaults are the reference demo, `compress`
//   invfree::Simulation sim = invfree::make_simulation(scene);
//   for (int k = 0; k < 100; ++k) invfree::step(sim);
//
// The core's worker threads are a setting of the program (one per core by default):
//   invfree::set_thread_count(4);  // before the first step; results do not depend on it
//
// Scene files (TOML) and the built-in scenes (assets/scenes/) are read by the separate
// invfree_scene_io library (scene_io/scene_file.h, scene_io/builtin_scenes.h), which the
// core never includes.
#pragma once

#include "linalg/parallel.h"
#include "scene/initial_state.h"
#include "scene/scene.h"
#include "simulation.h"
#include "triangle_fields.h"
