// The one-line idea of the built-in scenes that are not chapters of the course
// (course.h): the shapes of issue 27. The live panel shows it under the scene picker, as it
// shows a chapter's idea; a scene with none shows nothing.
#pragma once

#include <string_view>

namespace invfree::live {

struct SceneIdea {
  const char* scene;
  const char* idea;
};

inline constexpr SceneIdea kSceneIdeas[] = {
    {"ring", "an O-ring squashed until its hole closes: the hole's boundary is in self-contact"},
    {"c-shape", "a thick C squashed until its jaws meet, kept apart by self-contact"},
    {"plate-hole", "a plate pulled at both ends: colour by stress to see 3x at the hole's edge"},
    {"bunny", "an SVG outline meshed by CGAL, dropped on the ground"},
};

// The idea of a scene name, or nullptr.
inline const char* scene_idea(std::string_view scene) {
  for (const auto& s : kSceneIdeas)
    if (scene == s.scene) return s.idea;
  return nullptr;
}

}  // namespace invfree::live
