// The ORCA benchmark's peer side (issue 16): RVO2-3D on the random-cube scenario, timed.
//
//   random_cube AGENTS STEPS SEED [SPACING]
//
// Agents on a jittered cubic lattice of spacing SPACING (default 4, ≥ 4: no pair starts
// closer than 2 radii),
// each heading for the lattice point of a random permutation of the agents (a counter-based
// hash of SEED, the same one the Rust side uses: scripts/bench-orca.sh). Sphere.cc's agent
// defaults: neighborDist 15, maxNeighbors 10, timeHorizon 10, radius 1.5, maxSpeed 2;
// timeStep 0.125; prefVelocity = goal − position, normalised when longer than 1. doStep is
// RVO2-3D's own (OpenMP: set OMP_NUM_THREADS). Only the steps are timed. Overlaps: pairs
// closer than 2 radii after a step, counted with a hash grid (not timed).
// Prints one JSON line.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <unordered_map>
#include <vector>

#include <RVO.h>

namespace {
const float RADIUS = 1.5F;

std::uint32_t mix32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

float unit(std::uint32_t seed, std::uint32_t i, std::uint32_t k) {
  return static_cast<float>(mix32(mix32(seed ^ 0x9e3779b9U) ^ (i * 3U + k)) >> 8) /
         16777216.0F;
}

std::uint64_t overlaps(RVO::RVOSimulator *sim) {
  const float cell = 2.0F * RADIUS;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (x * 73856093) ^ (y * 19349663) ^ (z * 83492791);
  };
  const std::size_t n = sim->getNumAgents();
  std::vector<std::int64_t> cx(n), cy(n), cz(n);
  for (std::size_t i = 0; i < n; ++i) {
    const RVO::Vector3 p = sim->getAgentPosition(i);
    cx[i] = static_cast<std::int64_t>(std::floor(p.x() / cell));
    cy[i] = static_cast<std::int64_t>(std::floor(p.y() / cell));
    cz[i] = static_cast<std::int64_t>(std::floor(p.z() / cell));
    grid[key(cx[i], cy[i], cz[i])].push_back(i);
  }
  std::uint64_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const RVO::Vector3 p = sim->getAgentPosition(i);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(key(cx[i] + dx, cy[i] + dy, cz[i] + dz));
          if (it == grid.end()) continue;
          for (std::size_t j : it->second)
            if (j > i && RVO::absSq(sim->getAgentPosition(j) - p) < cell * cell) ++count;
        }
  }
  return count;
}
}  // namespace

int main(int argc, char **argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: random_cube AGENTS STEPS SEED [SPACING]\n");
    return 64;
  }
  const std::size_t n = std::strtoul(argv[1], nullptr, 10);
  const int steps = std::atoi(argv[2]);
  const std::uint32_t seed = static_cast<std::uint32_t>(std::strtoul(argv[3], nullptr, 10));
  const float SPACING = argc == 5 ? std::strtof(argv[4], nullptr) : 4.0F;
  const std::size_t side = static_cast<std::size_t>(std::ceil(std::cbrt(static_cast<double>(n))));
  RVO::RVOSimulator sim;
  sim.setTimeStep(0.125F);
  sim.setAgentDefaults(15.0F, 10U, 10.0F, RADIUS, 2.0F);
  std::vector<RVO::Vector3> lattice;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = static_cast<float>(i % side), y = static_cast<float>(i / side % side),
                z = static_cast<float>(i / (side * side));
    lattice.emplace_back(SPACING * (x + 0.25F * (unit(seed, i, 0) - 0.5F)),
                         SPACING * (y + 0.25F * (unit(seed, i, 1) - 0.5F)),
                         SPACING * (z + 0.25F * (unit(seed, i, 2) - 0.5F)));
    sim.addAgent(lattice.back());
  }
  // Goals: a Fisher-Yates permutation of the lattice points.
  std::vector<std::size_t> perm(n);
  for (std::size_t i = 0; i < n; ++i) perm[i] = i;
  for (std::size_t i = n; i > 1; --i) {
    const std::size_t j = mix32(seed ^ static_cast<std::uint32_t>(i)) % i;
    std::swap(perm[i - 1], perm[j]);
  }
  std::uint64_t total_overlaps = 0;
  double seconds = 0.0;
  for (int s = 0; s < steps; ++s) {
    for (std::size_t i = 0; i < n; ++i) {
      RVO::Vector3 g = lattice[perm[i]] - sim.getAgentPosition(i);
      if (RVO::absSq(g) > 1.0F) g = RVO::normalize(g);
      sim.setAgentPrefVelocity(i, g);
    }
    const auto t0 = std::chrono::steady_clock::now();
    sim.doStep();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total_overlaps += overlaps(&sim);
  }
  std::printf("{\"impl\": \"RVO2-3D\", \"agents\": %zu, \"steps\": %d, \"seconds\": %.6f, "
              "\"agent_steps_per_s\": %.1f, \"overlaps\": %llu, \"spacing\": %g}\n",
              n, steps, seconds, static_cast<double>(n) * steps / seconds,
              static_cast<unsigned long long>(total_overlaps), SPACING);
  return 0;
}
