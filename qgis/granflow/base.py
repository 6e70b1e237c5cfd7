# SPDX-License-Identifier: GPL-3.0-or-later
"""What the algorithms share: the case parameters (DEM, release, optional
entrainment, resistance, dam, path, split point; friction, density, cell
size, stop criterion, end time), their checks, and the gfRunCase run with
its progress and Cancel."""
import os
import re
import shutil

from qgis.core import (QgsProcessing, QgsProcessingAlgorithm, QgsProcessingException,
                       QgsProcessingParameterDefinition, QgsProcessingParameterEnum,
                       QgsProcessingParameterFeatureSource, QgsProcessingParameterField,
                       QgsProcessingParameterNumber, QgsProcessingParameterRasterLayer)

from .inputs import MARKER, CaseInputs, InputError
from .runner import Cancelled, failure, run_tool

FRICTIONS = ['samosATAuto', 'samosAT', 'samosATMedium', 'samosATSmall']


def num(v):
    """A number as the command line takes it (200, 0.01, 1e-05)."""
    return '%.15g' % v


class GranflowAlgorithm(QgsProcessingAlgorithm):
    """The provider's algorithms: their group, help and helpers."""

    def group(self):
        return ''

    def groupId(self):
        return ''

    HELP = ''

    def shortHelpString(self):
        # one line per paragraph: the dialog's help panel breaks lines where the text does
        return ' '.join(self.HELP.split())

    def createInstance(self):
        return type(self)()

    def helpUrl(self):
        return 'file://' + os.path.normpath(os.path.join(os.path.dirname(__file__), os.pardir, os.pardir,
                                                         'doc', 'guide', 'qgis.md'))

    def has_value(self, parameters, name):
        v = parameters.get(name)
        return v is not None and v != '' and not (hasattr(v, 'isNull') and v.isNull())

    def parameter_names(self):
        return [p.name() for p in self.parameterDefinitions()]

    def advanced(self, param):
        param.setFlags(param.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
        self.addParameter(param)

    # ---- the case parameters ------------------------------------------------
    def add_case_parameters(self, ranks=True):
        P = QgsProcessingParameterFeatureSource
        self.addParameter(QgsProcessingParameterRasterLayer('DEM', 'DEM (elevation raster, projected CRS in metres)'))
        self.addParameter(P('RELEASE', 'Release areas', [QgsProcessing.TypeVectorPolygon]))
        self.addParameter(QgsProcessingParameterField(
            'THICKNESS_FIELD', 'Release thickness field [m] (default: the field \'thickness\')', None, 'RELEASE',
            QgsProcessingParameterField.Numeric, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            'THICKNESS', 'Release thickness [m] for every polygon (instead of a field)',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.addParameter(P('ENTRAINMENT', 'Entrainment areas (simType ent)', [QgsProcessing.TypeVectorPolygon],
                            optional=True))
        self.advanced(QgsProcessingParameterField(
            'ENT_THICKNESS_FIELD', 'Entrainment thickness field [m] (default: the field \'thickness\')', None,
            'ENTRAINMENT', QgsProcessingParameterField.Numeric, optional=True))
        self.advanced(QgsProcessingParameterNumber(
            'ENT_THICKNESS', 'Entrainment thickness [m] for every polygon (instead of a field)',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.addParameter(P('RESISTANCE', 'Resistance areas, forests (simType res)',
                            [QgsProcessing.TypeVectorPolygon], optional=True))
        self.addParameter(P('DAM', 'Dam crown line (burnt into the DEM)', [QgsProcessing.TypeVectorLine],
                            optional=True))
        self.addParameter(P('PATH', 'Avalanche path (line from the release down: the path analysis)',
                            [QgsProcessing.TypeVectorLine], optional=True))
        self.addParameter(P('SPLIT_POINT', 'Split point (the runout area starts at the beta point below it)',
                            [QgsProcessing.TypeVectorPoint], optional=True))
        friction = QgsProcessingParameterEnum('FRICTION', 'Friction (samosAT set)', FRICTIONS, False,
                                              'samosATAuto', False)
        friction.setUsesStaticStrings(True)
        self.addParameter(friction)
        self.addParameter(QgsProcessingParameterNumber('RHO', 'Density [kg/m3]', QgsProcessingParameterNumber.Double,
                                                       200.0, False, 1e-6))
        self.addParameter(QgsProcessingParameterNumber(
            'CELL_SIZE', 'Mesh cell size [m] (a multiple of the DEM\'s; empty: the DEM\'s)',
            QgsProcessingParameterNumber.Double, None, True, 0.0))
        self.addParameter(QgsProcessingParameterNumber(
            'STOP_FRACTION', 'Stop when the kinetic energy falls below this fraction of its peak',
            QgsProcessingParameterNumber.Double, 0.01, False, 1e-12, 0.999999))
        self.addParameter(QgsProcessingParameterNumber('END_TIME', 'End time (the cap) [s]',
                                                       QgsProcessingParameterNumber.Double, 200.0, False, 1e-6))
        self.advanced(QgsProcessingParameterNumber(
            'THRESHOLD', 'Affected area: peak thickness at least [m]', QgsProcessingParameterNumber.Double,
            0.1, False, 1e-9))
        if ranks:
            self.advanced(QgsProcessingParameterNumber('NP', 'Solver processes (MPI ranks)',
                                                       QgsProcessingParameterNumber.Integer, 1, False, 1))

    def case_inputs(self, parameters, context):
        return CaseInputs(self, parameters, context)

    def checkParameterValues(self, parameters, context):
        ok, msg = super().checkParameterValues(parameters, context)
        if not ok:
            return ok, msg
        try:
            self.check(parameters, context)
        except InputError as e:
            return False, str(e)
        return True, ''

    def check(self, parameters, context):
        """Refuses bad input (InputError, the command-line tools' words)."""
        if 'DEM' in self.parameter_names() and 'RELEASE' in self.parameter_names():
            self.case_inputs(parameters, context).check()

    def case_options(self, parameters, context, inputs):
        """gfRunCase's options for the parameters."""
        opts = ['-friction', self.parameterAsEnumString(parameters, 'FRICTION', context),
                '-rho', num(self.parameterAsDouble(parameters, 'RHO', context))]
        if self.has_value(parameters, 'CELL_SIZE') and self.parameterAsDouble(parameters, 'CELL_SIZE', context) > 0:
            opts += ['-cellSize', num(self.parameterAsDouble(parameters, 'CELL_SIZE', context))]
        opts += ['-stopFraction', num(self.parameterAsDouble(parameters, 'STOP_FRACTION', context)),
                 '-endTime', num(self.parameterAsDouble(parameters, 'END_TIME', context)),
                 '-threshold', num(self.parameterAsDouble(parameters, 'THRESHOLD', context))]
        if inputs.sim_type() != 'null':
            opts += ['-simType', inputs.sim_type()]
        if inputs.dam is not None:
            opts += ['-dam']
        if 'NP' in self.parameter_names():
            n = self.parameterAsInt(parameters, 'NP', context)
            if n > 1:
                opts += ['-np', str(n)]
        return opts

    # ---- the gfRunCase run ---------------------------------------------------
    def run_case(self, parameters, context, feedback, lo=0.0, hi=100.0):
        """Writes the inputs into the output folder, runs gfRunCase on it;
        returns (folder, run folder, output lines).  Cancel stops the run and
        removes what it wrote (the run folder, the inputs, the folder when
        the algorithm made it)."""
        inputs = self.case_inputs(parameters, context)
        inputs.check()
        folder = os.path.abspath(self.parameterAsString(parameters, 'OUTPUT', context))
        made = not os.path.exists(folder)
        os.makedirs(folder, exist_ok=True)
        inputs.write(folder, context, feedback)
        end = self.parameterAsDouble(parameters, 'END_TIME', context)
        steps = {'gfTerrainMesh:': 0.02, 'makeFaMesh:': 0.03, 'gfSetRelease:': 0.05,
                 'wrote postProcessing/hazardMaps': 0.96, 'path analysis (gfPathAnalysis': 0.98}

        def progress(line):
            m = re.match(r'\s*granflow: t = ([-+0-9.eE]+) s', line)
            if m:
                f = 0.05 + 0.9 * min(1.0, float(m.group(1)) / end)
            else:
                f = next((v for k, v in steps.items() if line.startswith(k)), None)
                if f is None:
                    return None
            return lo + (hi - lo) * f
        args = ['gfRunCase'] + self.case_options(parameters, context, inputs) + [folder]
        try:
            rc, lines = run_tool(args, feedback, progress)
        except Cancelled:
            remove_outputs(folder, made, ['run'], feedback)
            raise QgsProcessingException('Cancelled: the run was stopped and {} removed'
                                         .format(folder if made else os.path.join(folder, 'run')))
        if rc != 0:
            raise QgsProcessingException('gfRunCase failed: {} (logs in {})'
                                         .format(failure('gfRunCase', lines), os.path.join(folder, 'run')))
        return folder, os.path.join(folder, 'run'), lines


def remove_outputs(folder, made, names, feedback):
    """After a cancelled run: the named folders in folder, the inputs the
    plugin wrote, and the folder itself when the algorithm made it."""
    if made:
        shutil.rmtree(folder, ignore_errors=True)
        feedback.pushInfo('removed {}'.format(folder))
        return
    for n in names + ['Inputs']:
        p = os.path.join(folder, n)
        if n == 'Inputs' and not os.path.exists(os.path.join(p, MARKER)):
            continue
        if os.path.isdir(p):
            shutil.rmtree(p, ignore_errors=True)
            feedback.pushInfo('removed {}'.format(p))
