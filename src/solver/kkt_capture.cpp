#include "fesd_trajopt/solver/kkt_capture.h"

namespace fesd {

namespace {
thread_local KktCapture* watching = nullptr;
}  // namespace

KktCapture::KktCapture(int keep) : keep_(keep), outer_(watching) {
  watching = this;
}

KktCapture::~KktCapture() {
  watching = outer_;
}

KktCapture* KktCapture::active() {
  return watching;
}

void KktCapture::addMatrix(Matrix matrix) {
  matrices_.push_back(std::move(matrix));
}

}  // namespace fesd
