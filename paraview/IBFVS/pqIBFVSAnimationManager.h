// Keeps the ParaView GUI rendering while a view shows a visible IBFVS
// representation: one IBFVS frame per render, so the texture moves on its
// own (in pvbatch and pvpython each Render() call advances it instead).
#ifndef pqIBFVSAnimationManager_h
#define pqIBFVSAnimationManager_h

#include <QObject>
#include <QSet>
#include <QTimer>

class pqView;

class pqIBFVSAnimationManager : public QObject {
  Q_OBJECT
 public:
  explicit pqIBFVSAnimationManager(QObject* parent = nullptr);
  ~pqIBFVSAnimationManager() override;

  void onStartup() {}
  void onShutdown() {}

 private Q_SLOTS:
  void onViewAdded(pqView* view);
  void onViewRemoved(pqView* view);
  void onRenderEnded();
  void renderAnimatedViews();

 private:
  QSet<pqView*> Views;
  QSet<pqView*> Pending;
  QTimer Timer;
};

#endif
