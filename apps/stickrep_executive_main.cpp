// stickrep-executive: the mission executive.
#include "executive/executive_node.h"
#include "runtime/process.h"

int main(int argc, char** argv) {
  return stickrep::runtime::RunProcess(argc, argv, "executive",
                                       stickrep::executive::MakeExecutiveNode);
}
