module Lamp_01(){

color("#c1cdcd")
cylinder(1,10,10, center= true);

color("#c1cdcd")
translate([0,0,20])
cylinder(40,1,1, center= true);

color("#ce5a57")
translate([0,0,40])
cylinder(2,8,8, center= true);



difference(){
color("#e47025")
translate([0,0,40])
cylinder(15,10,9, center= true);


color("#e47025")
translate([0,0,40])
cylinder(17,8,7, center= true);

}

}

Lamp_01();
