<?xml version="1.0" encoding="UTF-8"?>
<core:CityModel xmlns:core="http://www.opengis.net/citygml/1.0" xmlns:bldg="http://www.opengis.net/citygml/building/1.0" xmlns:gml="http://www.opengis.net/gml" xmlns:xlink="http://www.w3.org/1999/xlink">
  <gml:boundedBy><gml:Envelope srsName="urn:adv:crs:ETRS89_UTM32*DE_DHHN2016_NH*GCG2016"><gml:lowerCorner>325000 5729000 18</gml:lowerCorner><gml:upperCorner>326000 5730000 30</gml:upperCorner></gml:Envelope></gml:boundedBy>
  <!-- a comment with <tags> &amp; a dash - inside -->
  <core:cityObjectMember>
    <bldg:Building gml:id="DENW_gable">
      <bldg:measuredHeight uom="urn:adv:uom:m">5.0</bldg:measuredHeight>
      <bldg:lod2Solid><gml:Solid><gml:exterior><gml:CompositeSurface>
        <gml:surfaceMember xlink:href="#DENW_gable_poly_0"/>
        <gml:surfaceMember xlink:href="#DENW_gable_poly_1"/>
        <gml:surfaceMember xlink:href="#DENW_gable_poly_2"/>
        <gml:surfaceMember xlink:href="#DENW_gable_poly_3"/>
        <gml:surfaceMember xlink:href="#DENW_gable_poly_4"/>
        <gml:surfaceMember xlink:href="#DENW_gable_poly_5"/>
        <gml:surfaceMember xlink:href="#DENW_gable_poly_6"/>
      </gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod2Solid>
      <bldg:boundedBy><bldg:GroundSurface gml:id="DENW_gable_poly_0_s"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
        <gml:Polygon gml:id="DENW_gable_poly_0"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325100.000 5729100.000 20.000 325100.000 5729106.000 20.000 325108.000 5729106.000 20.000 325108.000 5729100.000 20.000 325100.000 5729100.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>
      </gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:GroundSurface></bldg:boundedBy>
      <bldg:boundedBy><bldg:WallSurface gml:id="DENW_gable_poly_1_s"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
        <gml:Polygon gml:id="DENW_gable_poly_1"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325100.000 5729100.000 20.000 325108.000 5729100.000 20.000 325108.000 5729100.000 23.000 325100.000 5729100.000 23.000 325100.000 5729100.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>
      </gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:WallSurface></bldg:boundedBy>
      <bldg:boundedBy><bldg:WallSurface gml:id="DENW_gable_poly_2_s"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
        <gml:Polygon gml:id="DENW_gable_poly_2"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325108.000 5729106.000 20.000 325100.000 5729106.000 20.000 325100.000 5729106.000 23.000 325108.000 5729106.000 23.000 325108.000 5729106.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>
      </gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:WallSurface></bldg:boundedBy>
      <bldg:boundedBy><bldg:WallSurface gml:id="DENW_gable_poly_3_s"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
        <gml:Polygon gml:id="DENW_gable_poly_3"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325108.000 5729100.000 20.000 325108.000 5729106.000 20.000 325108.000 5729106.000 23.000 325108.000 5729103.000 25.000 325108.000 5729100.000 23.000 325108.000 5729100.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>
      </gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:WallSurface></bldg:boundedBy>
      <bldg:boundedBy><bldg:WallSurface gml:id="DENW_gable_poly_4_s"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
        <gml:Polygon gml:id="DENW_gable_poly_4"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325100.000 5729106.000 20.000 325100.000 5729100.000 20.000 325100.000 5729100.000 23.000 325100.000 5729103.000 25.000 325100.000 5729106.000 23.000 325100.000 5729106.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>
      </gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:WallSurface></bldg:boundedBy>
      <bldg:boundedBy><bldg:RoofSurface gml:id="DENW_gable_poly_5_s"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
        <gml:Polygon gml:id="DENW_gable_poly_5"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325100.000 5729100.000 23.000 325108.000 5729100.000 23.000 325108.000 5729103.000 25.000 325100.000 5729103.000 25.000 325100.000 5729100.000 23.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>
      </gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:RoofSurface></bldg:boundedBy>
      <bldg:boundedBy><bldg:RoofSurface gml:id="DENW_gable_poly_6_s"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
        <gml:Polygon gml:id="DENW_gable_poly_6"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325108.000 5729106.000 23.000 325100.000 5729106.000 23.000 325100.000 5729103.000 25.000 325108.000 5729103.000 25.000 325108.000 5729106.000 23.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon>
      </gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:RoofSurface></bldg:boundedBy>
    </bldg:Building>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <bldg:Building gml:id="DENW_nosemantics">
      <bldg:measuredHeight uom="urn:adv:uom:m">5.0</bldg:measuredHeight>
      <bldg:lod2Solid><gml:Solid><gml:exterior><gml:CompositeSurface>
        <gml:surfaceMember><gml:Polygon gml:id="DENW_nosemantics_poly_0"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325200.000 5729100.000 20.000 325200.000 5729106.000 20.000 325210.000 5729106.000 20.000 325210.000 5729100.000 20.000 325200.000 5729100.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon gml:id="DENW_nosemantics_poly_1"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325200.000 5729100.000 23.000 325210.000 5729100.000 23.000 325210.000 5729106.000 23.000 325200.000 5729106.000 23.000 325200.000 5729100.000 23.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon gml:id="DENW_nosemantics_poly_2"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325200.000 5729100.000 20.000 325210.000 5729100.000 20.000 325210.000 5729100.000 23.000 325200.000 5729100.000 23.000 325200.000 5729100.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon gml:id="DENW_nosemantics_poly_3"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325210.000 5729100.000 20.000 325210.000 5729106.000 20.000 325210.000 5729106.000 23.000 325210.000 5729100.000 23.000 325210.000 5729100.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon gml:id="DENW_nosemantics_poly_4"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325210.000 5729106.000 20.000 325200.000 5729106.000 20.000 325200.000 5729106.000 23.000 325210.000 5729106.000 23.000 325210.000 5729106.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
        <gml:surfaceMember><gml:Polygon gml:id="DENW_nosemantics_poly_5"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">325200.000 5729106.000 20.000 325200.000 5729100.000 20.000 325200.000 5729100.000 23.000 325200.000 5729106.000 23.000 325200.000 5729106.000 20.000</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
      </gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod2Solid>
    </bldg:Building>
  </core:cityObjectMember>
</core:CityModel>
