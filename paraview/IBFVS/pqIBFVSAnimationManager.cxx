#include "pqIBFVSAnimationManager.h"

#include "pqApplicationCore.h"
#include "pqRenderView.h"
#include "pqRepresentation.h"
#include "pqServerManagerModel.h"
#include "pqView.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMRepresentationProxy.h"

#include <cstring>

namespace {
bool shows_ibfvs(pqView* view) {
  for (pqRepresentation* repr : view->getRepresentations()) {
    auto* proxy = vtkSMRepresentationProxy::SafeDownCast(repr->getProxy());
    if (!proxy || !proxy->GetProperty("Representation") || !proxy->GetProperty("Visibility")) {
      continue;
    }
    const char* type = vtkSMPropertyHelper(proxy, "Representation").GetAsString();
    if (type && std::strcmp(type, "IBFVS") == 0 &&
        vtkSMPropertyHelper(proxy, "Visibility").GetAsInt() != 0) {
      return true;
    }
  }
  return false;
}
}  // namespace

pqIBFVSAnimationManager::pqIBFVSAnimationManager(QObject* parent) : QObject(parent) {
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model, SIGNAL(preViewAdded(pqView*)), this, SLOT(onViewAdded(pqView*)));
  QObject::connect(model, SIGNAL(preViewRemoved(pqView*)), this, SLOT(onViewRemoved(pqView*)));
  for (pqView* view : model->findItems<pqView*>()) {
    this->onViewAdded(view);
  }
  // The next frame once the event loop is idle: the GUI stays responsive,
  // and a render that takes long simply lowers the frame rate.
  this->Timer.setSingleShot(true);
  this->Timer.setInterval(0);
  QObject::connect(&this->Timer, SIGNAL(timeout()), this, SLOT(renderAnimatedViews()));
}

pqIBFVSAnimationManager::~pqIBFVSAnimationManager() = default;

void pqIBFVSAnimationManager::onViewAdded(pqView* view) {
  if (dynamic_cast<pqRenderView*>(view)) {
    this->Views.insert(view);
    QObject::connect(view, SIGNAL(endRender()), this, SLOT(onRenderEnded()));
  }
}

void pqIBFVSAnimationManager::onViewRemoved(pqView* view) {
  if (this->Views.remove(view)) {
    QObject::disconnect(view, SIGNAL(endRender()), this, SLOT(onRenderEnded()));
  }
  this->Pending.remove(view);
}

void pqIBFVSAnimationManager::onRenderEnded() {
  auto* view = qobject_cast<pqView*>(this->sender());
  if (view && this->Views.contains(view) && shows_ibfvs(view)) {
    this->Pending.insert(view);
    this->Timer.start();
  }
}

void pqIBFVSAnimationManager::renderAnimatedViews() {
  const QSet<pqView*> views = this->Pending;
  this->Pending.clear();
  for (pqView* view : views) {
    if (this->Views.contains(view)) {
      view->render();
    }
  }
}
