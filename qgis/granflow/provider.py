# SPDX-License-Identifier: GPL-3.0-or-later
"""The Processing provider "granflow": Avalanche simulation, Path analysis,
Probability map, Back-calculate an event, Potential release areas,
Regional hazard indication map; its setting "granflow folder" (GRANFLOW_DIR)."""
import os

from qgis.core import QgsProcessingProvider
from qgis.PyQt.QtGui import QIcon

from .calibration import Calibration
from .path_analysis import PathAnalysis
from .probability import ProbabilityMap
from .regional_map import RegionalMap
from .release_areas import ReleaseAreas
from .runner import SETTING_DIR
from .simulation import Simulation


class GranflowProvider(QgsProcessingProvider):

    def id(self):
        return 'granflow'

    def name(self):
        return 'granflow'

    def longName(self):
        return 'granflow: avalanche simulation on terrain'

    def icon(self):
        return QIcon(os.path.join(os.path.dirname(__file__), 'icon.svg'))

    def load(self):
        try:
            from processing.core.ProcessingConfig import ProcessingConfig, Setting
            ProcessingConfig.settingIcons[self.name()] = self.icon()
            ProcessingConfig.addSetting(Setting(
                self.name(), SETTING_DIR,
                'granflow folder (GRANFLOW_DIR; empty: the environment variable, or the checkout the plugin is in)',
                '', valuetype=Setting.FOLDER))
            ProcessingConfig.readSettings()
        except ImportError:
            pass
        self.refreshAlgorithms()
        return True

    def unload(self):
        try:
            from processing.core.ProcessingConfig import ProcessingConfig
            ProcessingConfig.removeSetting(SETTING_DIR)
        except ImportError:
            pass

    def loadAlgorithms(self):
        for alg in (Simulation(), PathAnalysis(), ProbabilityMap(), Calibration(), ReleaseAreas(), RegionalMap()):
            self.addAlgorithm(alg)
