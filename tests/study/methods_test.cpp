// The method table (each method is only scene settings) and the embedded stress scenes.
#include "app/study/methods.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "app/format_number.h"
#include "app/study/stability.h"
#include "app/study/stress_scenes.h"
#include "scene_io/scene_file.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

TEST(Methods, EachIsAValidSetOfSceneOverrides) {
  std::set<std::string> names;
  for (const Method& m : study_methods()) {
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate " << m.name;
    SceneDef s;
    s.projection = HessianProjection::None;  // a scene setting must not leak into a method
    s.inversion_filter = false;
    s.integrator = Integrator::SymplecticEuler;
    s.model = Model::Arap;
    s.has_mass_spring = true;  // a course scene's springs must not leak in either
    EXPECT_EQ(apply_method(m, s, false), "") << m.name;
    EXPECT_EQ(find_method(m.name), &m);
    SceneDef again;
    EXPECT_EQ(apply_method(m, again, false), "");
    again.h = s.h;
    EXPECT_TRUE(again == s) << m.name << ": the result depends on the scene's own solver settings";
  }
  EXPECT_EQ(names.size(), 9u);
  EXPECT_EQ(find_method("nonexistent"), nullptr);
}

TEST(Methods, TheStabilitySweepAddsTheSpringsAfterTheStudysMethods) {
  const auto study = study_methods();
  const auto stability = stability_methods();
  ASSERT_GT(stability.size(), study.size());
  for (size_t k = 0; k < study.size(); ++k)
    EXPECT_EQ(&stability[k], &study[k]) << "the study's rows come first, in their order";
  const Method* springs = find_method("mass-spring");
  ASSERT_NE(springs, nullptr);
  EXPECT_TRUE(std::any_of(stability.begin() + static_cast<long>(study.size()), stability.end(),
                          [&](const Method& m) { return &m == springs; }));
  for (const Method& m : study) EXPECT_NE(&m, springs) << "the study does not take the springs";
  // The solver settings are the lecture's and do not come from the scene; the spring
  // stiffness, like E and nu for the other rows, does.
  SceneDef s;
  s.projection = HessianProjection::None;
  s.inversion_filter = false;
  s.integrator = Integrator::SymplecticEuler;
  s.step_expansion = false;
  s.spring_stiffness = 2e4;
  ASSERT_EQ(apply_method(*springs, s, true), "");
  SceneDef lecture;
  ASSERT_EQ(apply_method(*find_method("lecture"), lecture, true), "");
  EXPECT_TRUE(s.has_mass_spring);
  EXPECT_FALSE(s.has_triangle_elasticity());
  EXPECT_FALSE(lecture.has_mass_spring);
  EXPECT_EQ(s.projection, lecture.projection);
  EXPECT_EQ(s.inversion_filter, lecture.inversion_filter);
  EXPECT_EQ(s.integrator, lecture.integrator);
  EXPECT_EQ(s.step_expansion, lecture.step_expansion);
  EXPECT_EQ(s.friction_crossing_stop, lecture.friction_crossing_stop);
  EXPECT_DOUBLE_EQ(s.h, SceneDef{}.h);
  EXPECT_DOUBLE_EQ(s.spring_stiffness, 2e4);
  EXPECT_EQ(method_model(*springs), "mass-spring");
  EXPECT_EQ(method_model(*find_method("lecture")), "neo-hookean");
}

TEST(Methods, EachMethodSetsItsModelSolverAndIntegrator) {
  auto with = [](const char* name, bool substeps = false) {
    SceneDef s;
    EXPECT_EQ(apply_method(*find_method(name), s, substeps), "");
    return s;
  };
  SceneDef s = with("lecture");
  EXPECT_EQ(s.model, Model::NeoHookean);
  EXPECT_EQ(s.projection, HessianProjection::Diagonal);
  EXPECT_TRUE(s.inversion_filter);
  EXPECT_EQ(s.integrator, Integrator::ImplicitEuler);
  EXPECT_TRUE(s.step_expansion);
  EXPECT_TRUE(s.friction_crossing_stop);
  const SceneDef plain = with("plain-line-search");
  EXPECT_FALSE(plain.step_expansion);
  EXPECT_FALSE(plain.friction_crossing_stop);
  EXPECT_EQ(plain.projection, HessianProjection::Diagonal);
  EXPECT_EQ(with("full-eigen-clamp").projection, HessianProjection::Full);
  EXPECT_EQ(with("no-projection").projection, HessianProjection::None);
  EXPECT_FALSE(with("no-inversion-filter").inversion_filter);
  EXPECT_EQ(with("symplectic-euler").integrator, Integrator::SymplecticEuler);
  EXPECT_DOUBLE_EQ(with("symplectic-euler", true).h, SceneDef{}.h / 20.0);
  EXPECT_DOUBLE_EQ(with("lecture", true).h, SceneDef{}.h);
  EXPECT_EQ(with("linear").model, Model::Linear);
  EXPECT_EQ(with("arap").model, Model::Arap);
  EXPECT_EQ(with("stable-neo-hookean").model, Model::StableNeoHookean);
  EXPECT_EQ(method_command_line(*find_method("no-projection")),
            "--set material.model=neo-hookean --set solver.projection=none --set "
            "solver.inversion_filter=true "
            "--set solver.integrator=implicit-euler --set solver.step_expansion=true "
            "--set solver.friction_crossing_stop=true --set mass_spring.enabled=false");
}

TEST(StressScenes, EveryFileIsEmbeddedAndLoads) {
  std::set<std::string> on_disk;
  for (const auto& e : std::filesystem::directory_iterator(
           std::string(::invfree::test::source_dir()) + "/assets/scenes")) {
    const std::string name = e.path().stem().string();
    if (name.rfind("stress-", 0) == 0 && e.path().extension() == ".toml") on_disk.insert(name);
  }
  std::set<std::string> embedded;
  for (const StressScene& s : stress_scenes()) {
    // Besides the stress files, only course scenes and the O-ring (the built-in scenes' own
    // files).
    if (s.name.rfind("stress-", 0) == 0)
      embedded.insert(s.name);
    else
      EXPECT_TRUE(s.name.rfind("course-", 0) == 0 || s.name == "ring") << s.name;
    EXPECT_NE(s.label, s.name) << s.name << " has no column heading in stress_scenes.cpp";
    std::string error;
    auto scene = load_stress_scene(s, &error);
    ASSERT_TRUE(scene) << error;
    EXPECT_EQ(scene->name, s.name);
    // The file on disk is the very text that was embedded.
    const SceneLoad file = load_scene(std::string(::invfree::test::source_dir()) +
                                      "/assets/scenes/" + s.name + ".toml");
    ASSERT_TRUE(file.scene) << file.error;
    EXPECT_TRUE(*file.scene == *scene) << s.name << ": rebuild after editing a stress scene";
  }
  EXPECT_EQ(embedded, on_disk);
  EXPECT_GE(embedded.size(), 11u);
}

TEST(StressScenes, EachChangesTheDemoTheWayItsNameSays) {
  std::map<std::string, SceneDef> s;
  for (const StressScene& st : stress_scenes()) {
    std::string error;
    s[st.name] = *load_stress_scene(st, &error);
  }
  EXPECT_DOUBLE_EQ(s["stress-h0.05"].h, 0.05);
  EXPECT_DOUBLE_EQ(s["stress-h0.1"].h, 0.1);
  double E = 0.0, nu = 0.0;
  young_poisson_from_lame(s["stress-nu0.49"].lame, &E, &nu);
  EXPECT_NEAR(nu, 0.49, 1e-12);
  young_poisson_from_lame(s["stress-nu0.499"].lame, &E, &nu);
  EXPECT_NEAR(nu, 0.499, 1e-12);
  const SceneDef& sq10 = s["stress-squash10"];
  EXPECT_NEAR(sq10.ceiling_stop - sq10.ground_y, 0.1 * sq10.side, 1e-12);
  const SceneDef& sq5 = s["stress-squash5"];
  EXPECT_NEAR(sq5.ceiling_stop - sq5.ground_y, 0.05 * sq5.side, 1e-12);
  EXPECT_NEAR(s["stress-impact"].initial_velocity.norm(), 20.0, 1e-12);
  young_poisson_from_lame(s["stress-soft"].lame, &E, &nu);
  EXPECT_NEAR(E, 1e3, 1e-6);
  young_poisson_from_lame(s["stress-stiff"].lame, &E, &nu);
  EXPECT_NEAR(E / 1e8, 1.0, 1e-12);
  EXPECT_GT(s["stress-jitter"].jitter, 0.0);
  SceneDef inverted = s["stress-jitter-inverted"];
  inverted.model = Model::NeoHookean;
  EXPECT_NE(validate_scene(inverted), "")
      << "the inverted start must be one neo-Hookean cannot run";
  SceneDef jitter = s["stress-jitter"];
  jitter.model = Model::NeoHookean;
  EXPECT_EQ(validate_scene(jitter), "");
}

TEST(StressScenes, DurationCoversTheCeilingTravel) {
  SceneDef s;  // ceiling 0.6 -> -0.7 at 0.5 m/s: 2.6 s, plus 0.5 s
  EXPECT_NEAR(stability_duration(s), 3.1, 1e-9);
  s.h = 0.1;
  EXPECT_NEAR(stability_duration(s), 3.1, 1e-9);
  s.has_ceiling = false;
  EXPECT_NEAR(stability_duration(s), 2.0, 1e-9);
}

TEST(StressScenes, QuickRunsReachTheSquashOfEveryScene) {
  for (const StressScene& stress : stress_scenes()) {
    std::string error;
    const auto s = load_stress_scene(stress, &error);
    ASSERT_TRUE(s) << error;
    ASSERT_TRUE(s->has_ceiling && s->ceiling_velocity < 0.0) << stress.name;
    const double squash = (s->ceiling_y - s->ceiling_stop) / -s->ceiling_velocity;
    const double quick = quick_stability_duration(*s);
    EXPECT_GE(quick, squash - 1e-9) << stress.name << ": the quick run stops before the squash";
    EXPECT_LT(quick, squash + s->h + 1e-9) << stress.name << ": whole steps, no settling";
    EXPECT_LT(quick, stability_duration(*s)) << stress.name;
  }
}

TEST(StabilityTable, FailuresAreGivenInSceneTimeAndInTheMethodsSteps) {
  StabilityCell implicit;
  implicit.fail_step = 249;
  implicit.h = 0.01;
  EXPECT_EQ(failure_time(implicit), "t = 2.49 s, step 249");
  StabilityCell substeps;
  substeps.fail_step = 2202;
  substeps.h = 0.0005;
  substeps.substeps = 20;
  EXPECT_EQ(failure_time(substeps), "t = 1.1 s, substep 2,202 of h/20");
  EXPECT_EQ(format_for_people(336935.4), "336,935");
  EXPECT_EQ(format_for_people(-1234567.0), "-1,234,567");
  EXPECT_EQ(format_for_people(10.0), "10");
  EXPECT_EQ(format_for_people(0.125), "0.125");
  StabilityResult quick;
  quick.quick = true;
  EXPECT_NE(stability_markdown(quick).find("**A quick run**"), std::string::npos);
  EXPECT_EQ(stability_markdown(StabilityResult{}).find("quick run"), std::string::npos);
}

}  // namespace
}  // namespace invfree
