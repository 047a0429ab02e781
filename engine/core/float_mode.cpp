#include "engine/core/float_mode.h"

namespace fibrenet {

void FlushDenormalsToZero() {
  FlushDenormalsToZeroOnThisThread();
#pragma omp parallel
  FlushDenormalsToZeroOnThisThread();
}

}  // namespace fibrenet
