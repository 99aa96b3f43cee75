// stickrep-sonar: the sonar process.
#include "sonar/sonar_node.h"
#include "runtime/process.h"

int main(int argc, char** argv) {
  return stickrep::runtime::RunProcess(argc, argv, "sonar", stickrep::sonar::MakeSonarNode);
}
