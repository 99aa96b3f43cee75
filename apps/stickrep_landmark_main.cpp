// stickrep-landmark: the landmark process.
#include "landmark/landmark_node.h"
#include "runtime/process.h"

int main(int argc, char** argv) {
  return stickrep::runtime::RunProcess(argc, argv, "landmark", stickrep::landmark::MakeLandmarkNode);
}
