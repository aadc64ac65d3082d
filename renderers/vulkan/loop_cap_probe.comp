#version 450
// loop_cap_probe.h: one invocation counts a loop of push.trips iterations, a run-time count the
// compiler cannot fold. A driver with a per-invocation loop cap ends the loop early.
layout(local_size_x = 1, local_size_y = 1, local_size_z = 1) in;

layout(push_constant) uniform ProbePush {
  uint trips;
} push;

layout(std430, binding = 0) buffer ProbeResult {
  uint done;
};

void main() {
  uint n = 0u;
  for (uint i = 0u; i < push.trips; ++i) n++;
  done = n;
}
