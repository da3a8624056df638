#pragma once

#include <string>
#include <vector>

#include <ros/publisher.h>
#include <rviz/panel.h>

class QLabel;
class QTimer;

namespace rviz
{
class Property;
}

namespace biovision_monitor
{
/// An rviz panel that makes rviz's per-display status (the Ok / Warn / Error under each display in the
/// Displays panel, otherwise seen only in the GUI) observable: once a second it walks the display tree and
/// publishes, latched, on `~display_status` (the rviz node's private namespace) a
/// diagnostic_msgs/DiagnosticArray: first "Global Status" (rviz's own: the fixed frame), then one
/// DiagnosticStatus per display, groups' displays included (`name` = the display's name, `hardware_id` =
/// its class, `level` = rviz's level, 0 Ok / 1 Warn / 2 Error as in DiagnosticStatus, `message` = that
/// word, one `values` entry per status line: key = its name, value = "<level word>: <text>"). A display
/// whose class could not be loaded (rviz's FailedDisplay, which has no status list) is Error with the
/// loader's message; a display that never set a status is Ok. The panel shows the worst level and the
/// number of displays in error. biovision_bringup's monitor_rviz rostest reads it (issue #20).
class DisplayStatusPanel : public rviz::Panel
{
  Q_OBJECT
public:
  explicit DisplayStatusPanel(QWidget* parent = nullptr);
  void onInitialize() override;

private Q_SLOTS:
  void report();

private:
  QLabel* label_;
  QTimer* timer_;
  ros::Publisher publisher_;
};
}  // namespace biovision_monitor
