# SPDX-License-Identifier: GPL-3.0-or-later
"""The plugin: it adds the granflow Processing provider (in QGIS and in
qgis_process, which calls initProcessing)."""
from qgis.core import QgsApplication

from .provider import GranflowProvider


class GranflowPlugin:

    def __init__(self, iface=None):
        self.iface = iface
        self.provider = None

    def initProcessing(self):
        if self.provider is None:
            self.provider = GranflowProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)

    def initGui(self):
        self.initProcessing()

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
