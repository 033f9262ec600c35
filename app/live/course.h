// The course: the built-in scenes that walk through the public solid-sim-tutorial's
// chapters in order (course-0's three demos, course-1 ... course-5, the lecture's demo `compress`, then `stack` and
// `stack-friction`), each with
// its chapter's one-line idea. The live window's picker lists them first, in chapter order,
// and its panel shows the selected chapter's idea (docs/scenes.md tables the same chapters),
// `compress`, the lecture's own scene, included.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace invfree::live {

struct CourseChapter {
  const char* scene;
  int chapter;
  const char* idea;  // nullptr: none shown
};

inline constexpr CourseChapter kCourse[] = {
    {"course-0-free-fall", 0, "explicit symplectic Euler: v += h g, then x += h v"},
    {"course-0-spring", 0, "a particle on a Hooke spring: the spring's force in the same update"},
    {"course-0-mass-spring", 0,
     "a mass-spring square hanging from two corners, explicit: stable only while h is small"},
    {"course-1-mass-spring", 1, "implicit Euler as minimisation: a stretched mass-spring square"},
    {"course-2-dirichlet", 2, "Dirichlet boundary: hanging from two fixed corners"},
    {"course-3-contact", 3, "contact: the IPC barrier and the filtered line search"},
    {"course-4-friction", 4, "lagged friction: sliding down a slope"},
    {"course-5-moving-dirichlet", 5, "a moving Dirichlet boundary: squashed by the ceiling"},
    {"compress", 6, "inversion-free: det F > 0 in every step"},
    {"stack", 7, "self-contact: two squares kept apart by the point-edge barrier and CCD"},
    {"stack-friction", 8, "friction between the bodies, lagged as the ground's"},
    {"course-9-affine", 9,
     "reduced DOF: Newton in the 6 affine unknowns (anchor triangle drawn): affine body dynamics"},
    {"course-9-quadratic", 9, "reduced DOF: quadratic polynomials of the rest shape, 12 unknowns"},
    {"course-9-cubic", 9, "reduced DOF: cubic polynomials, 20 unknowns: closer to the full model"},
    {"course-9-modal", 9,
     "modal reduction: the rest Hessian's 12 softest modes (rigid ones included) as the basis"},
};

// The chapter of a scene name, or nullptr when it is not one of the course's.
inline const CourseChapter* course_chapter(std::string_view scene) {
  for (const auto& c : kCourse)
    if (scene == c.scene) return &c;
  return nullptr;
}

// The course's scenes first, in kCourse's order (chapter order; chapter 0's three demos in
// the tutorial's order), then the others in their given order.
inline void put_course_first(std::vector<std::string>& names) {
  std::stable_sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    const CourseChapter* ca = course_chapter(a);
    const CourseChapter* cb = course_chapter(b);
    return ca && (!cb || ca < cb);
  });
}

}  // namespace invfree::live
