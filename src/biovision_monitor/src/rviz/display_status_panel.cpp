#include "biovision_monitor/rviz/display_status_panel.hpp"

#include <algorithm>

#include <QLabel>
#include <QTimer>
#include <QVBoxLayout>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/node_handle.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/failed_display.h>
#include <rviz/properties/status_list.h>
#include <rviz/visualization_manager.h>

namespace biovision_monitor
{
namespace
{
// One DiagnosticStatus from a StatusList: its level and one value per status line.
void addStatus(const rviz::StatusList& list, diagnostic_msgs::DiagnosticStatus& s)
{
  s.level = std::max(s.level, static_cast<int8_t>(std::clamp(static_cast<int>(list.getLevel()), 0, 2)));
  for (int k = 0; k < list.numChildren(); ++k)
    if (const auto* line = qobject_cast<const rviz::StatusProperty*>(list.childAt(k)))
    {
      diagnostic_msgs::KeyValue v;
      v.key = line->getNameStd();
      v.value = rviz::StatusProperty::statusWord(line->getLevel()).toStdString() + ": " +
                line->getValue().toString().toStdString();
      s.values.push_back(v);
    }
}

// Every display below `group` (groups included, depth first) as one DiagnosticStatus named after it: the
// level of its StatusList (a display that never set a status has none: Ok), and Error for a FailedDisplay
// (its class could not be loaded; rviz shows that only as a red row, with no status list).
void collect(const rviz::Property& group, std::vector<diagnostic_msgs::DiagnosticStatus>& out)
{
  for (int i = 0; i < group.numChildren(); ++i)
  {
    const auto* display = qobject_cast<const rviz::Display*>(group.childAt(i));
    if (!display)
      continue;
    diagnostic_msgs::DiagnosticStatus s;
    s.name = display->getNameStd();
    s.hardware_id = display->getClassId().toStdString();
    s.level = diagnostic_msgs::DiagnosticStatus::OK;
    if (dynamic_cast<const rviz::FailedDisplay*>(display))
    {
      s.level = diagnostic_msgs::DiagnosticStatus::ERROR;
      diagnostic_msgs::KeyValue v;
      v.key = "Class";
      v.value = "Error: " + display->getDescription().toStdString();
      s.values.push_back(v);
    }
    for (int k = 0; k < display->numChildren(); ++k)
      if (const auto* list = qobject_cast<const rviz::StatusList*>(display->childAt(k)))
        addStatus(*list, s);
    s.message = rviz::StatusProperty::statusWord(static_cast<rviz::StatusProperty::Level>(s.level)).toStdString();
    out.push_back(s);
    collect(*display, out);
  }
}
}  // namespace

DisplayStatusPanel::DisplayStatusPanel(QWidget* parent)
  : rviz::Panel(parent), label_(new QLabel("display status: waiting", this)), timer_(new QTimer(this))
{
  auto* layout = new QVBoxLayout;
  layout->addWidget(label_);
  setLayout(layout);
  connect(timer_, SIGNAL(timeout()), this, SLOT(report()));
}

void DisplayStatusPanel::onInitialize()
{
  publisher_ = ros::NodeHandle("~").advertise<diagnostic_msgs::DiagnosticArray>("display_status", 1, true);
  timer_->start(1000);
}

void DisplayStatusPanel::report()
{
  if (!vis_manager_)
    return;
  rviz::DisplayGroup* root = vis_manager_->getRootDisplayGroup();
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  // rviz's own status (the fixed frame) is a StatusList of the root group, "Global Status".
  diagnostic_msgs::DiagnosticStatus global;
  global.name = "Global Status";
  global.level = diagnostic_msgs::DiagnosticStatus::OK;
  for (int k = 0; k < root->numChildren(); ++k)
    if (const auto* list = qobject_cast<const rviz::StatusList*>(root->childAt(k)))
      addStatus(*list, global);
  global.message =
      rviz::StatusProperty::statusWord(static_cast<rviz::StatusProperty::Level>(global.level)).toStdString();
  array.status.push_back(global);
  collect(*root, array.status);
  int worst = 0, errors = 0;
  for (const auto& s : array.status)
  {
    worst = std::max(worst, static_cast<int>(s.level));
    errors += s.level == diagnostic_msgs::DiagnosticStatus::ERROR;
  }
  label_->setText(QString("%1 status lists, worst: %2, in error: %3")
                      .arg(array.status.size())
                      .arg(rviz::StatusProperty::statusWord(static_cast<rviz::StatusProperty::Level>(worst)))
                      .arg(errors));
  publisher_.publish(array);
}
}  // namespace biovision_monitor

PLUGINLIB_EXPORT_CLASS(biovision_monitor::DisplayStatusPanel, rviz::Panel)
