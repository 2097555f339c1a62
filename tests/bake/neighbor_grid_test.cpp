#include <algorithm>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/neighbor_grid.h"

using namespace swell::bake;

namespace {

struct Cloud {
    std::vector<double> x, y;
};

Cloud randomCloud(std::size_t n, const Box& box, unsigned seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> ux(box.x0, box.x1), uy(box.y0, box.y1);
    Cloud c;
    for (std::size_t i = 0; i < n; ++i) {
        c.x.push_back(ux(gen));
        c.y.push_back(uy(gen));
    }
    return c;
}

} // namespace

TEST(NeighborGrid, ListsEqualBruteForce) {
    const Box domain{0.0, 0.0, 1.0, 0.5};
    const Cloud c = randomCloud(2000, domain, 7);
    const double radius = 0.035;
    NeighborGrid grid;
    grid.configure(domain, radius, c.x.size(), 128);
    ASSERT_TRUE(grid.build(c.x, c.y, radius));
    for (std::size_t i = 0; i < c.x.size(); ++i) {
        std::set<std::uint32_t> expected;
        for (std::size_t j = 0; j < c.x.size(); ++j) {
            const double dx = c.x[j] - c.x[i], dy = c.y[j] - c.y[i];
            if (j != i && dx * dx + dy * dy < radius * radius)
                expected.insert(static_cast<std::uint32_t>(j));
        }
        const auto list = grid.neighbors(i);
        const std::set<std::uint32_t> got(list.begin(), list.end());
        ASSERT_EQ(got, expected) << "particle " << i;
        ASSERT_EQ(got.size(), list.size()) << "duplicates in the list of particle " << i;
    }
}

TEST(NeighborGrid, ShortListsAreTheFullListsCutAtTheShortRadiusInTheSameOrder) {
    const Box domain{0.0, 0.0, 1.0, 0.5};
    const Cloud c = randomCloud(2000, domain, 13);
    const double radius = 0.035;
    const double shortRadius = 0.025;
    NeighborGrid grid;
    grid.configure(domain, radius, c.x.size(), 128);
    ASSERT_TRUE(grid.build(c.x, c.y, radius, shortRadius));
    std::size_t shortTotal = 0, fullTotal = 0;
    for (std::size_t i = 0; i < c.x.size(); ++i) {
        std::vector<std::uint32_t> expected;
        for (std::uint32_t j : grid.neighbors(i)) {
            const double dx = c.x[j] - c.x[i], dy = c.y[j] - c.y[i];
            if (dx * dx + dy * dy < shortRadius * shortRadius)
                expected.push_back(j);
        }
        const auto got = grid.shortNeighbors(i);
        ASSERT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), expected) << "particle " << i;
        shortTotal += got.size();
        fullTotal += grid.neighbors(i).size();
    }
    EXPECT_GT(shortTotal, 0U);
    EXPECT_LT(shortTotal, fullTotal);
    EXPECT_THROW(grid.build(c.x, c.y, radius, 2.0 * radius), std::invalid_argument);
    ASSERT_TRUE(grid.build(c.x, c.y, radius)); // no short radius: empty short lists
    for (std::size_t i = 0; i < c.x.size(); ++i)
        EXPECT_TRUE(grid.shortNeighbors(i).empty());
}

TEST(NeighborGrid, SortedOrderGroupsCellsAndListsAreRankOrdered) {
    const Box domain{-1.0, -1.0, 1.0, 1.0};
    const Cloud c = randomCloud(1500, domain, 11);
    NeighborGrid grid;
    grid.configure(domain, 0.1, c.x.size(), 128);
    ASSERT_TRUE(grid.build(c.x, c.y, 0.1));
    const auto order = grid.sorted();
    ASSERT_EQ(order.size(), c.x.size());
    // A permutation, non-decreasing in cell index, and rank() inverts it.
    std::vector<bool> seen(c.x.size(), false);
    int lastCell = -1;
    for (std::size_t k = 0; k < order.size(); ++k) {
        const std::uint32_t i = order[k];
        ASSERT_FALSE(seen[i]);
        seen[i] = true;
        const int cell = grid.cellOf(c.x[i], c.y[i]);
        ASSERT_GE(cell, lastCell);
        lastCell = cell;
        ASSERT_EQ(grid.rank(i), k);
    }
    for (std::size_t i = 0; i < c.x.size(); ++i) {
        const auto list = grid.neighbors(i);
        for (std::size_t k = 1; k < list.size(); ++k)
            ASSERT_LT(grid.rank(list[k - 1]), grid.rank(list[k]));
    }
}

TEST(NeighborGrid, RebuildAfterMotionGivesNewLists) {
    const Box domain{0.0, 0.0, 1.0, 1.0};
    std::vector<double> x{0.1, 0.12, 0.5}, y{0.1, 0.1, 0.5};
    NeighborGrid grid;
    grid.configure(domain, 0.05, 3, 8);
    ASSERT_TRUE(grid.build(x, y, 0.05));
    EXPECT_EQ(grid.neighbors(0).size(), 1u);
    EXPECT_EQ(grid.neighbors(2).size(), 0u);
    x[2] = 0.11;
    y[2] = 0.11;
    ASSERT_TRUE(grid.build(x, y, 0.05));
    EXPECT_EQ(grid.neighbors(0).size(), 2u);
    EXPECT_EQ(grid.neighbors(2).size(), 2u);
}

TEST(NeighborGrid, ReportsOverflowInsteadOfTruncatingSilently) {
    const Box domain{0.0, 0.0, 1.0, 1.0};
    std::vector<double> x(20, 0.5), y(20, 0.5);
    for (std::size_t i = 0; i < x.size(); ++i)
        x[i] += 1e-4 * static_cast<double>(i);
    NeighborGrid grid;
    grid.configure(domain, 0.1, x.size(), 8);
    EXPECT_FALSE(grid.build(x, y, 0.1));
    EXPECT_LT(grid.overflowParticle(), x.size());
}

TEST(NeighborGrid, RejectsParticlesOutsideTheDomainAndBadConfiguration) {
    NeighborGrid grid;
    EXPECT_THROW(grid.configure(Box{0, 0, 0, 1}, 0.1, 10, 8), std::invalid_argument);
    EXPECT_THROW(grid.configure(Box{0, 0, 1, 1}, 0.0, 10, 8), std::invalid_argument);
    grid.configure(Box{0, 0, 1, 1}, 0.1, 2, 8);
    std::vector<double> x{0.5, 1.5}, y{0.5, 0.5};
    EXPECT_THROW(grid.build(x, y, 0.1), std::out_of_range);
    EXPECT_THROW(grid.build(x, y, 0.2), std::invalid_argument); // radius above the cell size
}
