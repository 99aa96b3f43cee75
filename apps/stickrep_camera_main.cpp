// stickrep-camera: the camera process.
#include "camera/camera_node.h"
#include "runtime/process.h"

int main(int argc, char** argv) {
  return stickrep::runtime::RunProcess(argc, argv, "camera", stickrep::camera::MakeCameraNode);
}
