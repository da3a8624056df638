# The Python helpers of biovision_ros_common (catkin_python_setup; not for pip).
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["biovision_ros_common"], package_dir={"": "src"}))
