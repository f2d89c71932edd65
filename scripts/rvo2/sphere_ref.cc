// R-T7 reference driver: RVO2-3D's examples/Sphere.cc, scaled down (sphere radius 15, polar
// step 0.3 rad: 45 agents), run for STEPS steps, printing every agent's position after each
// step (line 0: the initial positions) as the hex bits of the IEEE-754 float components, so
// the Rust test reads them back exactly. Agent defaults, time step and preferred velocities are
// Sphere.cc's: neighborDist 15, maxNeighbors 10, timeHorizon 10, radius 1.5, maxSpeed 2,
// timeStep 0.125, prefVelocity = goal − position, normalised when longer than 1.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include <RVO.h>

namespace {
const float RVO3D_TWO_PI = 6.28318530717958647692F;
const float SPHERE = 15.0F;
const float POLAR_STEP = 0.3F;
const int STEPS = 100;

std::uint32_t bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

void print(RVO::RVOSimulator *sim) {
  for (std::size_t i = 0U; i < sim->getNumAgents(); ++i) {
    const RVO::Vector3 p = sim->getAgentPosition(i);
    std::printf(i == 0U ? "%08x %08x %08x" : " %08x %08x %08x", bits(p.x()),
                bits(p.y()), bits(p.z()));
  }
  std::printf("\n");
}
}  // namespace

int main() {
  RVO::RVOSimulator *sim = new RVO::RVOSimulator();
  std::vector<RVO::Vector3> goals;
  sim->setTimeStep(0.125F);
  sim->setAgentDefaults(15.0F, 10U, 10.0F, 1.5F, 2.0F);
  for (std::size_t i = 0U; i * POLAR_STEP < RVO3D_TWO_PI / 2.0F; ++i) {
    const float z = SPHERE * std::cos(i * POLAR_STEP);
    const float r = SPHERE * std::sin(i * POLAR_STEP);
    for (std::size_t j = 0U; j < r / 2.5F; ++j) {
      const float x = r * std::cos(j * RVO3D_TWO_PI / (r / 2.5F));
      const float y = r * std::sin(j * RVO3D_TWO_PI / (r / 2.5F));
      sim->addAgent(RVO::Vector3(x, y, z));
      goals.push_back(-sim->getAgentPosition(sim->getNumAgents() - 1U));
    }
  }
  std::printf("# RVO2-3D Sphere (scaled): %zu agents, %d steps, dt 0.125, neighborDist 15, "
              "maxNeighbors 10, timeHorizon 10, radius 1.5, maxSpeed 2; per line: x y z "
              "float bits of every agent\n",
              sim->getNumAgents(), STEPS);
  print(sim);
  for (int s = 0; s < STEPS; ++s) {
    for (std::size_t i = 0U; i < sim->getNumAgents(); ++i) {
      RVO::Vector3 g = goals[i] - sim->getAgentPosition(i);
      if (RVO::absSq(g) > 1.0F) {
        g = RVO::normalize(g);
      }
      sim->setAgentPrefVelocity(i, g);
    }
    sim->doStep();
    print(sim);
  }
  delete sim;
  return 0;
}
