#!/usr/bin/env python3
"""Writes the Collada meshes the test robots use (run it here to make them again).

bumper_z_up.dae: a flat bumper ring (outer radius 0.17 m, inner 0.14 m, 6 cm tall, from z = 0.01 to 0.07),
labelled Z_UP as most ROS packages export their meshes. block_{z_up,y_up}.dae: the same asymmetric block
(x 0.05..0.45, y -0.1..0.1, z 0..0.06) under each label; block_mm.dae: that block in millimetres with
<unit meter="0.001">. Read in the URDF's frame (as rviz and Gazebo do), the two labels give the same shape.
"""
import math


def collada(vertices, triangles, up, meter=1.0):
    pos = " ".join(f"{c:.6g}" for v in vertices for c in v)
    idx = " ".join(str(i) for t in triangles for i in t)
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>
    <unit name="{'meter' if meter == 1.0 else 'millimeter'}" meter="{meter:g}"/>
    <up_axis>{up}</up_axis>
  </asset>
  <library_geometries>
    <geometry id="shape" name="shape">
      <mesh>
        <source id="shape-positions">
          <float_array id="shape-positions-array" count="{3 * len(vertices)}">{pos}</float_array>
          <technique_common>
            <accessor source="#shape-positions-array" count="{len(vertices)}" stride="3">
              <param name="X" type="float"/>
              <param name="Y" type="float"/>
              <param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="shape-vertices">
          <input semantic="POSITION" source="#shape-positions"/>
        </vertices>
        <triangles count="{len(triangles)}">
          <input semantic="VERTEX" source="#shape-vertices" offset="0"/>
          <p>{idx}</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="Scene" name="Scene">
      <node id="shape-node" name="shape">
        <instance_geometry url="#shape"/>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene>
    <instance_visual_scene url="#Scene"/>
  </scene>
</COLLADA>
"""


def block(x0, x1, y0, y1, z0, z1):
    v = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return v, [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]


def ring(outer, inner, z0, z1, n=32):
    v = []
    for r, z in ((outer, z0), (outer, z1), (inner, z0), (inner, z1)):
        v += [(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n), z) for k in range(n)]
    t = []
    for k in range(n):
        j = (k + 1) % n
        for a, b in ((0, n), (2 * n, 3 * n), (n, 3 * n), (0, 2 * n)):  # outer and inner walls, top, bottom
            t += [(a + k, a + j, b + j), (a + k, b + j, b + k)]
    return v, t


if __name__ == "__main__":
    with open("bumper_z_up.dae", "w") as f:
        f.write(collada(*ring(0.17, 0.14, 0.01, 0.07), "Z_UP"))
    b = block(0.05, 0.45, -0.1, 0.1, 0.0, 0.06)
    for up, name in (("Z_UP", "block_z_up.dae"), ("Y_UP", "block_y_up.dae")):
        with open(name, "w") as f:
            f.write(collada(*b, up))
    mm = ([tuple(1000 * c for c in p) for p in b[0]], b[1])
    with open("block_mm.dae", "w") as f:
        f.write(collada(*mm, "Z_UP", 0.001))
