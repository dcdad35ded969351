// The test-time views: each is a signed permutation of x and y that keeps z, its inverse undoes it, every
// prefix the options allow is a group (so averaging over it is the same from any view), and patch features
// are transformed in their two vectors only.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "model/test_time_symmetry.h"

namespace lc2wf {
namespace {

PlaneSymmetry compose(const PlaneSymmetry& a, const PlaneSymmetry& b) {  // a after b
  PlaneSymmetry c;
  c.m = {a.m[0] * b.m[0] + a.m[1] * b.m[2], a.m[0] * b.m[1] + a.m[1] * b.m[3], a.m[2] * b.m[0] + a.m[3] * b.m[2],
         a.m[2] * b.m[1] + a.m[3] * b.m[3]};
  return c;
}

TEST(TestTimeSymmetry, EveryAllowedPrefixIsAGroupOfDistinctSignedPermutations) {
  for (int count : {1, 2, 4, 8}) {
    const std::vector<PlaneSymmetry> views = test_time_symmetries(count);
    ASSERT_EQ(views.size(), static_cast<size_t>(count));
    EXPECT_EQ(views[0].m, (std::array<int, 4>{1, 0, 0, 1}));  // the first view is the cloud as it is
    for (size_t i = 0; i < views.size(); ++i) {
      const auto& m = views[i].m;
      EXPECT_EQ(std::abs(m[0] * m[3] - m[1] * m[2]), 1) << count << " " << i;
      for (size_t j = 0; j < views.size(); ++j) {
        if (i != j) EXPECT_NE(views[i].m, views[j].m) << count << " " << i << " " << j;
        const PlaneSymmetry c = compose(views[i], views[j]);
        EXPECT_TRUE(std::any_of(views.begin(), views.end(), [&](const PlaneSymmetry& v) { return v.m == c.m; }))
            << "views " << i << " and " << j << " of " << count << " compose to a view outside the set";
      }
    }
  }
}

TEST(TestTimeSymmetry, InverseUndoesTheViewAndZStays) {
  for (const PlaneSymmetry& s : test_time_symmetries(8)) {
    double v[3] = {0.25, -1.5, 3.0};
    s.apply(v);
    EXPECT_EQ(v[2], 3.0);
    EXPECT_DOUBLE_EQ(v[0] * v[0] + v[1] * v[1], 0.25 * 0.25 + 1.5 * 1.5);
    s.apply_inverse(v);
    EXPECT_EQ(v[0], 0.25);
    EXPECT_EQ(v[1], -1.5);
  }
  double quarter[3] = {1.0, 0.0, 0.0};
  test_time_symmetries(8)[4].apply(quarter);  // a quarter turn, not a mirror
  EXPECT_EQ(quarter[0], 0.0);
  EXPECT_EQ(quarter[1], 1.0);
}

TEST(TestTimeSymmetry, RefusesOtherViewCounts) {
  for (int count : {0, 3, 5, 16, -1}) EXPECT_THROW(test_time_symmetries(count), std::invalid_argument) << count;
}

TEST(TestTimeSymmetry, FeaturesChangeInTheirTwoVectorsOnly) {
  // Two slots of a junction patch: [near - x (3), far - x (3), distance].
  std::vector<float> f = {1, 2, 3, 4, 5, 6, 0.5f, -1, -2, -3, -4, -5, -6, 0.25f};
  transform_patch_features(f, 7, test_time_symmetries(2)[1]);  // 180°: x and y change sign
  EXPECT_EQ(f, (std::vector<float>{-1, -2, 3, -4, -5, 6, 0.5f, 1, 2, -3, 4, 5, -6, 0.25f}));
  std::vector<float> pair = {1, 2, 3, 4, 5, 6};
  transform_patch_features(pair, 6, test_time_symmetries(8)[6]);  // the diagonal mirror swaps x and y
  EXPECT_EQ(pair, (std::vector<float>{2, 1, 3, 5, 4, 6}));
  std::vector<float> ragged(10);
  EXPECT_THROW(transform_patch_features(ragged, 7, test_time_symmetries(1)[0]), std::invalid_argument);
  EXPECT_THROW(transform_patch_features(ragged, 5, test_time_symmetries(1)[0]), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
