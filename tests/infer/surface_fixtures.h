// Hand-made building wireframes with known faces for the surface tests: a box, a gabled house, a hipped house,
// an L-shaped flat roof and a two-level flat roof. Each comes with its faces (vertex sets) and labels.
#pragma once

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf::testing {

struct FixtureBuilding {
  std::string name;
  Wireframe wireframe;
  std::vector<std::vector<int>> faces;  // expected faces (any order, any start, any direction)
  int roofs = 0, walls = 0, grounds = 0;
  std::array<int, 2> removable_edge{};  // an edge whose loss the face finder must repair
  std::array<int, 2> spurious_edge{};   // an edge that belongs to no face (new junction ids allowed: see spurious_point)
  bool spurious_to_new_point = false;   // spurious_edge[1] == junctions.size() is a new junction at spurious_point
  Vec3 spurious_point = Vec3::Zero();
};

inline Wireframe make_wireframe(const std::vector<Vec3>& v, const std::vector<std::array<int, 2>>& e) {
  Wireframe w;
  w.junctions = v;
  for (const auto& x : e) w.edges.push_back({std::min(x[0], x[1]), std::max(x[0], x[1])});
  return w;
}

inline FixtureBuilding box_building() {
  FixtureBuilding b;
  b.name = "box";
  b.wireframe = make_wireframe({{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}, {0, 0, 2.5}, {4, 0, 2.5}, {4, 3, 2.5}, {0, 3, 2.5}},
                               {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}});
  b.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  b.roofs = 1, b.walls = 4, b.grounds = 1;
  b.removable_edge = {0, 4};
  b.spurious_edge = {0, 6};  // through the inside
  return b;
}

inline FixtureBuilding gabled_building() {
  FixtureBuilding b;
  b.name = "gabled";
  b.wireframe = make_wireframe(
      {{0, 0, 0}, {6, 0, 0}, {6, 4, 0}, {0, 4, 0}, {0, 0, 3}, {6, 0, 3}, {6, 4, 3}, {0, 4, 3}, {0, 2, 5}, {6, 2, 5}},
      {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 5}, {2, 6}, {3, 7}, {4, 5}, {7, 6}, {4, 8}, {7, 8}, {5, 9}, {6, 9}, {8, 9}});
  b.faces = {{0, 1, 2, 3}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 8, 4}, {1, 2, 6, 9, 5}, {4, 5, 9, 8}, {7, 6, 9, 8}};
  b.roofs = 2, b.walls = 4, b.grounds = 1;
  b.removable_edge = {8, 9};
  b.spurious_edge = {0, 5};  // a diagonal across a wall
  return b;
}

inline FixtureBuilding hipped_building() {
  FixtureBuilding b;
  b.name = "hipped";
  b.wireframe = make_wireframe(
      {{0, 0, 0}, {8, 0, 0}, {8, 4, 0}, {0, 4, 0}, {0, 0, 3}, {8, 0, 3}, {8, 4, 3}, {0, 4, 3}, {2, 2, 5}, {6, 2, 5}},
      {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 5}, {2, 6}, {3, 7}, {4, 5}, {5, 6}, {6, 7}, {7, 4},
       {4, 8}, {7, 8}, {5, 9}, {6, 9}, {8, 9}});
  b.faces = {{0, 1, 2, 3}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7},
             {4, 5, 9, 8}, {6, 7, 8, 9}, {4, 8, 7}, {5, 6, 9}};
  b.roofs = 4, b.walls = 4, b.grounds = 1;
  b.removable_edge = {4, 8};
  b.spurious_edge = {4, 9};  // a diagonal across a roof facet
  return b;
}

inline FixtureBuilding l_shaped_building() {
  FixtureBuilding b;
  b.name = "l_shaped";
  const std::vector<Vec2> outline{{0, 0}, {6, 0}, {6, 3}, {3, 3}, {3, 6}, {0, 6}};
  std::vector<Vec3> v;
  for (const Vec2& p : outline) v.push_back({p.x(), p.y(), 0});
  for (const Vec2& p : outline) v.push_back({p.x(), p.y(), 3.2});
  std::vector<std::array<int, 2>> e;
  for (int i = 0; i < 6; ++i) {
    e.push_back({i, (i + 1) % 6});
    e.push_back({6 + i, 6 + (i + 1) % 6});
    e.push_back({i, 6 + i});
  }
  b.wireframe = make_wireframe(v, e);
  b.faces = {{0, 1, 2, 3, 4, 5}, {6, 7, 8, 9, 10, 11}};
  for (int i = 0; i < 6; ++i) b.faces.push_back({i, (i + 1) % 6, 6 + (i + 1) % 6, 6 + i});
  b.roofs = 1, b.walls = 6, b.grounds = 1;
  b.removable_edge = {8, 9};
  b.spurious_edge = {7, 12};  // a dangling edge from a roof corner to a new junction
  b.spurious_to_new_point = true;
  b.spurious_point = {8, -1, 4.5};
  return b;
}

inline FixtureBuilding two_level_building() {
  FixtureBuilding b;
  b.name = "two_level";
  // A: ground 0-3, low roof 4-7 (E F G H), tall roof 8-11 (I J K L)
  b.wireframe = make_wireframe({{0, 0, 0}, {8, 0, 0}, {8, 4, 0}, {0, 4, 0},
                                {8, 0, 3}, {8, 4, 3}, {4, 0, 3}, {4, 4, 3},
                                {0, 0, 6}, {4, 0, 6}, {4, 4, 6}, {0, 4, 6}},
                               {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 8}, {3, 11}, {1, 4}, {2, 5}, {6, 9}, {7, 10},
                                {4, 5}, {6, 4}, {7, 5}, {6, 7}, {8, 9}, {9, 10}, {10, 11}, {11, 8}});
  b.faces = {{0, 1, 2, 3}, {4, 5, 7, 6}, {8, 9, 10, 11}, {1, 2, 5, 4}, {6, 7, 10, 9}, {0, 3, 11, 8},
             {0, 1, 4, 6, 9, 8}, {3, 2, 5, 7, 10, 11}};
  b.roofs = 2, b.walls = 5, b.grounds = 1;
  b.removable_edge = {6, 7};
  b.spurious_edge = {8, 2};  // through the inside
  return b;
}

inline std::vector<FixtureBuilding> all_fixture_buildings() {
  return {box_building(), gabled_building(), hipped_building(), l_shaped_building(), two_level_building()};
}

inline Wireframe without_edge(Wireframe w, std::array<int, 2> e) {
  const std::array<int, 2> k{std::min(e[0], e[1]), std::max(e[0], e[1])};
  w.edges.erase(std::remove(w.edges.begin(), w.edges.end(), k), w.edges.end());
  return w;
}

inline Wireframe with_spurious_edge(const FixtureBuilding& b) {
  Wireframe w = b.wireframe;
  if (b.spurious_to_new_point) w.junctions.push_back(b.spurious_point);
  w.edges.push_back({std::min(b.spurious_edge[0], b.spurious_edge[1]), std::max(b.spurious_edge[0], b.spurious_edge[1])});
  return w;
}

}  // namespace lc2wf::testing
