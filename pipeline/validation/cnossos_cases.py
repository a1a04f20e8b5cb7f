"""NoiseModelling's own rolling-noise test expectations, as data (the CNOSSOS-EU check's reference).

NoiseModelling (Universite-Gustave-Eiffel/NoiseModelling, GPL-3), module noisemodelling-emission; its
inputs and expected band levels are ported here as data (no code):

* ``RailwayCnossosTest.java`` (src/test/java/org/noise_planet/noisemodelling/emission/railway/) at commit
  35d2da1b5d871927779430c7e7807b5765e2bdc1 (2026-07-30; the file last changed in da47fee8), tests
  ``Test_Cnossos_Rail_emission_section_1`` ... ``_5``, which load ``outdated/RailwayVehiclesCnossos_2015.json``
  and ``outdated/RailwayCnossosEU_2020.json`` (our pipeline/data/cnossos/).  They assert
  L = L_W,0 + 10 lg(nBUnit) + 10 lg(t) - 10 lg(1000 v nTracks) per band (``Utils.trainLWmperFreq``),
  energy-summed over vehicles in section_5, to 1e-4 dB; the speed used is min(v, vMaxInfra, vCommercial).
* ``EvaluateRailWaySourceCNOSSOSTest.java`` (src/test/java/org/noise_planet/noisemodelling/emission/) at
  commit f599472441c8739f662c000c94f59e92e6e8bfdf (2022-04-08, its last version; removed in 6773420e),
  which asserts L_W,0 per vehicle directly (4 decimals): sections 1, 2, 4 (200 km/h) and 5 (three vehicles).
  It ran on the 2021-era copy of the same tables; our current copy reproduces it to 5e-5 dB.

Only the ROLLING source of each test is ported (traction, aerodynamic and bridge are other sources); the
SNCF cases (section_6, OC1-OC7) use France's national tables, not the Directive's, and are not shipped.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.config.cnossos import rolling_power_bands
from solvers.radiation import rolling_cnossos as rc

NM_REPO = "Universite-Gustave-Eiffel/NoiseModelling"
NEW = ("noisemodelling-emission/src/test/java/org/noise_planet/noisemodelling/emission/railway/RailwayCnossosTest.java",
       "35d2da1b5d871927779430c7e7807b5765e2bdc1")
OLD = ("noisemodelling-emission/src/test/java/org/noise_planet/noisemodelling/emission/EvaluateRailWaySourceCNOSSOSTest.java",
       "f599472441c8739f662c000c94f59e92e6e8bfdf")
TOL_DB = 0.1


@dataclass(frozen=True)
class Veh:
    """One vehicle line of a Java test: vehCat, vehicleSpeed (km/h), nBUnit, period fraction t."""
    cat: str
    speed: float
    units: float = 1.0
    t: float = 1.0


@dataclass(frozen=True)
class Case:
    name: str            # Java test method (and period)
    source: tuple        # (file, commit)
    vehicles: tuple
    track: dict          # trackTransfer, railRoughness, impactNoise references
    v_infra: float
    v_commercial: float
    n_tracks: int
    expected: tuple      # 24 bands, 50 Hz ... 10 kHz
    per_vehicle: bool = False   # True: expected is L_W,0 of the one vehicle (old test)


T7R3I1 = {"transfer": "7", "rail_roughness": "3", "impact": "1"}
T7R4I1 = {"transfer": "7", "rail_roughness": "4", "impact": "1"}
S5_VEHICLES = {"D": (Veh("SNCF-BB66400", 80, 1, 0.4), Veh("RMR-Cat-1", 120, 1, 0.5), Veh("RMR-Cat-9-a", 100, 1, 0.2)),
               "E": (Veh("SNCF-BB66400", 80, 1, 0.3), Veh("RMR-Cat-1", 120, 1, 0.5), Veh("RMR-Cat-9-a", 100, 1, 0.3)),
               "N": (Veh("SNCF-BB66400", 80, 1, 0.25), Veh("RMR-Cat-1", 120, 1, 0.2), Veh("RMR-Cat-9-a", 100, 1, 0.7))}

CASES = (
    Case("Test_Cnossos_Rail_emission_section_1", NEW, (Veh("SNCF-BB66400", 80),), T7R3I1, 160, 140, 2, (
        46.62923937074308, 47.5930887825746, 49.48855395436553, 50.84525150627218, 48.290416823553656,
        47.55991120199147, 48.36598621415334, 53.685023895294904, 55.17947382327178, 56.44358069598965,
        57.381090582936295, 58.06233085323542, 59.82942366487711, 59.45435581560096, 56.541564191934896,
        52.173989709214666, 54.51129722944201, 53.2570463370446, 51.118153521942574, 48.73174211849708,
        49.13517759611298, 48.60046539576308, 48.58746317902302, 50.14566621392022)),
    Case("Test_Cnossos_Rail_emission_section_2", NEW, (Veh("SNCF-BB66400", 80),),
         {"transfer": "7", "rail_roughness": "3", "impact": "3"}, 160, 120, 2, (
        48.855812075460975, 49.80224950461141, 52.61908165678001, 54.982731704412586, 52.61987147312681,
        52.041501361148036, 53.19288499441544, 57.95824500346427, 58.13283629462971, 58.077111652037416,
        58.250150682153944, 58.69354673204066, 60.388651969482424, 59.76608857751005, 56.71229509132594,
        52.262588086680765, 54.5627556471335, 53.29375923552483, 51.141539208928265, 48.745028050980125,
        49.141647244090876, 48.601924082363865, 48.58782710304959, 50.14560443243711)),
    Case("Test_Cnossos_Rail_emission_section_3", NEW, (Veh("SNCF-BB66400", 80),), T7R3I1, 160, 120, 4, (
        43.61893941410327, 44.582788825934784, 46.478253997725716, 47.834951549632365, 45.28011686691384,
        44.549611245351656, 45.355686257513526, 50.67472393865509, 52.169173866631965, 53.43328073934984,
        54.37079062629648, 55.05203089659561, 56.8191237082373, 56.44405585896115, 53.53126423529508,
        49.163689752574854, 51.500997272802195, 50.24674638040479, 48.10785356530276, 45.72144216185727,
        46.12487763947317, 45.59016543912327, 45.577163222383206, 47.13536625728041)),
    Case("Test_Cnossos_Rail_emission_section_4 (day)", NEW, (Veh("SNCF-BB66400", 80, 1, 0.4),),
         {"transfer": "9", "rail_roughness": "3", "impact": "1"}, 160, 120, 2, (
        42.64047716756204, 43.59103735908428, 45.456174153991, 46.773857830747545, 44.20212586691305,
        43.07694967273832, 42.54462519449325, 47.92450477396579, 49.74087356604085, 54.05475982745676,
        57.841090649116026, 57.771236415461615, 57.85669468078028, 56.12813486229132, 52.72126638618079,
        47.75972514124385, 50.33326183725299, 49.08523837496412, 46.97538128072445, 44.5793134982533,
        45.004481967694915, 44.50787367671097, 44.5287841222723, 46.11962258959353)),
    Case("Test_Cnossos_Rail_emission_section_4 (evening)", NEW, (Veh("SNCF-BB66400", 80, 1, 0.3),),
         {"transfer": "9", "rail_roughness": "3", "impact": "1"}, 160, 120, 2, (
        41.39108980147904, 42.34164999300128, 44.206786787908, 45.524470464664546, 42.95273850083005,
        41.827562306655324, 41.29523782841025, 46.675117407882794, 48.49148619995785, 52.805372461373764,
        56.59170328303303, 56.521849049378616, 56.60730731469728, 54.87874749620832, 51.47187902009779,
        46.51033777516085, 49.08387447116999, 47.83585100888112, 45.72599391464145, 43.3299261321703,
        43.755094601611916, 43.25848631062797, 43.2793967561893, 44.870235223510534)),
    Case("Test_Cnossos_Rail_emission_section_4 (night)", NEW, (Veh("SNCF-BB66400", 80, 1, 0.25),),
         {"transfer": "9", "rail_roughness": "3", "impact": "1"}, 160, 120, 2, (
        40.59927734100279, 41.54983753252503, 43.41497432743175, 44.732658004188295, 42.1609260403538,
        41.03574984617907, 40.503425367934, 45.88330494740654, 47.6996737394816, 52.01356000089751,
        55.799890822556776, 55.730036588902365, 55.81549485422103, 54.08693503573207, 50.68006655962154,
        45.7185253146846, 48.29206201069374, 47.04403854840487, 44.9341814541652, 42.53811367169405,
        42.963282141135664, 42.46667385015172, 42.48758429571305, 44.07842276303428)),
    Case("Test_Cnossos_Rail_emission_section_5 (day, 3 vehicles summed)", NEW, S5_VEHICLES["D"], T7R4I1, 160, 120, 2, (
        47.71997843033826, 46.637350019740694, 47.57462749051441, 48.37035398021847, 46.26756512527347,
        46.231021285491536, 47.86579192688177, 52.487052374043586, 53.488856919653934, 54.60582219451978,
        56.07350114723665, 58.46378649956855, 62.755024418449956, 63.70786252484214, 61.80735449363346,
        58.68560995030353, 56.934883841636676, 54.84658995444764, 51.830594829509096, 49.969642427112504,
        48.54957338454732, 47.75658020373088, 47.89544088700445, 48.67590747414407)),
    Case("Test_Cnossos_Rail_emission_section_5 (evening, 3 vehicles summed)", NEW, S5_VEHICLES["E"], T7R4I1, 160, 120, 2, (
        47.8571829614869, 46.773205039062276, 47.65061271097261, 48.41688361760173, 46.32933646576278,
        46.28022349802543, 47.91165590399426, 52.32870371415995, 53.193078095746394, 54.26199790602617,
        55.84798703049516, 58.496779937215315, 62.94191660235764, 63.901269120719455, 62.01181168644282,
        58.892194681278255, 56.92203496269723, 54.83406505619752, 51.87274923380053, 50.01731005663079,
        48.38932689131972, 47.63016466691677, 47.751238073652125, 48.38987243332228)),
    Case("Test_Cnossos_Rail_emission_section_5 (night, 3 vehicles summed)", NEW, S5_VEHICLES["N"], T7R4I1, 160, 120, 2, (
        47.65504941580788, 46.52263037133977, 47.410602883575564, 48.44075766451791, 46.403473096977066,
        46.477035962374885, 48.16562342931819, 52.52404691923551, 53.48428196138525, 54.65273465783923,
        56.363119689612375, 58.960398517566645, 62.97519061980192, 63.521599596900884, 61.41409817229095,
        58.02824808516533, 55.85451052086385, 54.18421078705474, 51.97980699274502, 49.8322214851138,
        48.306533194735444, 47.956080531777864, 47.89683391435612, 48.574675637769815)),
    Case("Test_Cnossos_Rail_emission_section_1 (old)", OLD, (Veh("SNCF-BB66400", 80),), T7R3I1, 160, 120, 2, (
        98.6704, 99.6343, 101.5298, 102.8865, 100.3316, 99.6011, 100.4072, 105.7262, 107.2207, 108.4848, 109.4223,
        110.1035, 111.8706, 111.4956, 108.5828, 104.2152, 106.5525, 105.2982, 103.1594, 100.7729, 101.1764, 100.6417,
        100.6287, 102.1869), per_vehicle=True),
    Case("Test_Cnossos_Rail_emission_section_2 (old)", OLD, (Veh("SNCF-BB66400", 80),),
         {"transfer": "7", "rail_roughness": "3", "impact": "3"}, 160, 120, 2, (
        100.8970, 101.8434, 104.6603, 107.0239, 104.6611, 104.0827, 105.2341, 109.9994, 110.1740, 110.1183, 110.2914,
        110.7347, 112.4299, 111.8073, 108.7535, 104.3038, 106.6040, 105.3350, 103.1827, 100.7862, 101.1828, 100.6431,
        100.6290, 102.1868), per_vehicle=True),
    Case("Test_Cnossos_Rail_emission_section_4 (old, 200 km/h)", OLD, (Veh("SNCF-BB66400", 200),),
         {"transfer": "9", "rail_roughness": "3", "impact": "1"}, 200, 200, 2, (
        98.66110, 100.5681, 104.3908, 107.5565, 106.7391, 106.4557, 105.5468, 109.3204, 108.2763, 109.2614, 111.1101,
        112.5186, 117.3340, 121.3800, 123.5189, 122.9000, 126.9115, 122.9414, 117.8516, 111.8003, 107.3142, 105.8263,
        103.9313, 102.2640), per_vehicle=True),
    Case("Test_Cnossos_Rail_emission_section_5 (old, SNCF-BB66400 80 km/h)", OLD, (Veh("SNCF-BB66400", 80),), T7R4I1,
         160, 120, 2, (
        97.1163, 95.9284, 97.6691, 99.2991, 97.1440, 97.4508, 99.2167, 105.2093, 107.0484, 108.4798, 109.5263,
        110.2781, 112.0743, 111.6404, 108.6516, 104.1867, 106.4632, 105.1549, 102.952, 100.4917, 100.9441, 100.4491,
        100.4702, 102.0818), per_vehicle=True),
    Case("Test_Cnossos_Rail_emission_section_5 (old, RMR-Cat-1 120 km/h)", OLD, (Veh("RMR-Cat-1", 120),), T7R4I1,
         160, 120, 2, (
        102.3819, 101.3591, 102.0322, 102.2927, 100.1769, 99.86140, 101.3709, 104.9785, 104.7817, 105.1695, 107.2118,
        111.4597, 117.2867, 118.8195, 117.2068, 114.3600, 112.0048, 109.4634, 105.5892, 104.2252, 101.6110, 100.1356,
        100.5837, 100.3448), per_vehicle=True),
    Case("Test_Cnossos_Rail_emission_section_5 (old, RMR-Cat-9-a 100 km/h)", OLD, (Veh("RMR-Cat-9-a", 100),), T7R4I1,
         160, 120, 2, (
        100.0997, 98.93480, 99.69780, 100.8341, 98.85870, 98.98000, 100.6952, 104.5915, 105.3080, 106.4464, 108.5190,
        111.5829, 115.6512, 115.9799, 113.7622, 110.2023, 107.1972, 105.9335, 104.4154, 102.0925, 100.1482, 100.1865,
        99.95900, 100.3303), per_vehicle=True),
)


def ours(case: Case) -> np.ndarray:
    """The quantity the Java test asserts, from our rolling_power_bands with the test's inputs."""
    energy = np.zeros(rc.N_BANDS)
    for v in case.vehicles:
        speed = min(v.speed, case.v_infra, case.v_commercial)
        lw0 = rolling_power_bands(v.cat, case.track, speed)[1]
        if case.per_vehicle:
            return lw0
        level = lw0 + 10 * math.log10(v.units) + 10 * math.log10(v.t) - 10 * math.log10(1000 * v.speed * case.n_tracks)
        energy += 10.0 ** (level / 10.0)
    return 10.0 * np.log10(energy)
