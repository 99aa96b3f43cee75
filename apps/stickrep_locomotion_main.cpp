// stickrep-locomotion: the locomotion process.
#include "locomotion/locomotion_node.h"
#include "runtime/process.h"

int main(int argc, char** argv) {
  return stickrep::runtime::RunProcess(argc, argv, "locomotion", stickrep::locomotion::MakeLocomotionNode);
}
