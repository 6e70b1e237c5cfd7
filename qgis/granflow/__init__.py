# SPDX-License-Identifier: GPL-3.0-or-later
"""granflow's QGIS plugin: a Processing provider "granflow" whose algorithms
run granflow's command-line tools (doc/guide/qgis.md).  QGIS finds it through
QGIS_PLUGINPATH=$GRANFLOW_DIR/qgis (granflow's etc/bashrc sets it)."""


def classFactory(iface):
    from .plugin import GranflowPlugin
    return GranflowPlugin(iface)
