// stickrep-virtual-robot: the simulated hardware and world.
#include "runtime/process.h"
#include "virtual_robot/virtual_robot_node.h"

int main(int argc, char** argv) {
  return stickrep::runtime::RunProcess(argc, argv, "virtual_robot",
                                       stickrep::virtual_robot::MakeVirtualRobotNode);
}
