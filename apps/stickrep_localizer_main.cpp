// stickrep-localizer: the localizer process.
#include "localizer/localizer_node.h"
#include "runtime/process.h"

int main(int argc, char** argv) {
  return stickrep::runtime::RunProcess(argc, argv, "localizer",
                                       stickrep::localizer::MakeLocalizerNode);
}
